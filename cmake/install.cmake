# install.cmake — what `cmake --install` lays out (docs/library.md says the same for users):
#   bin/contactlab                                  the tool (full build only)
#   share/contactlab/scenes/                        scene files and scenes/experiments/ protocols
#   lib/udev/rules.d/70-contactlab.rules            USB access for the logged-in user
#   share/doc/contactlab/                           README.md, docs/, scenes/README.md, examples/
#   include/haptics/, include/drivers/, lib/*.a     the libraries and their headers
#   lib/cmake/ContactLab/                           find_package(ContactLab): ContactLab::haptics,
#                                                   ContactLab::wearable, ContactLab::drivers
# The haptics-only configuration installs the physics core (haptics + wearable) and its package.
include(CMakePackageConfigHelpers)

set(CONTACTLAB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ContactLab)
set(CONTACTLAB_DOC_DIR ${CMAKE_INSTALL_DATADIR}/doc/contactlab)
if(CONTACTLAB_HAPTICS_ONLY)
  set(CONTACTLAB_BUILD_DRIVERS OFF)
  set(CONTACTLAB_CONFIG_DRIVERS_NOTE "")
else()
  set(CONTACTLAB_BUILD_DRIVERS ON)
  set(CONTACTLAB_CONFIG_DRIVERS_NOTE " and ContactLab::drivers (devices, simulated rigs, the servo loop)")
endif()

# The libraries: ContactLab::<name>, headers under include/ keeping their folders.
set_target_properties(contactlab_haptics PROPERTIES EXPORT_NAME haptics)
set_target_properties(contactlab_wearable PROPERTIES EXPORT_NAME wearable)
set(CONTACTLAB_EXPORTED contactlab_haptics contactlab_wearable)
if(CONTACTLAB_BUILD_DRIVERS)
  set_target_properties(contactlab_drivers PROPERTIES EXPORT_NAME drivers)
  list(APPEND CONTACTLAB_EXPORTED contactlab_drivers)
endif()
install(TARGETS ${CONTACTLAB_EXPORTED} EXPORT ContactLabTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# haptics/verify/ is the tests' reference code, not part of the library.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/haptics/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/haptics
        FILES_MATCHING PATTERN "*.hpp" PATTERN "verify" EXCLUDE)
if(CONTACTLAB_BUILD_DRIVERS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/drivers/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/drivers
          FILES_MATCHING PATTERN "*.hpp")
endif()

install(EXPORT ContactLabTargets NAMESPACE ContactLab:: DESTINATION ${CONTACTLAB_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ContactLabConfig.cmake.in
  ${PROJECT_BINARY_DIR}/ContactLabConfig.cmake INSTALL_DESTINATION ${CONTACTLAB_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ContactLabConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)  # 0.x: a minor release may change the API
install(FILES ${PROJECT_BINARY_DIR}/ContactLabConfig.cmake ${PROJECT_BINARY_DIR}/ContactLabConfigVersion.cmake
        DESTINATION ${CONTACTLAB_CMAKE_DIR})

if(NOT CONTACTLAB_BUILD_DRIVERS)
  return()
endif()

# The tool and what it reads at run time: the scenes/ tree, found beside the binary
# (engine/app/data_path.hpp: BIN/../share/contactlab/).
install(TARGETS contactlab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/contactlab)
# udev reads /usr/lib/udev/rules.d (never multiarch), and /usr/local/lib/udev/rules.d not at all:
# a prefix other than /usr installs the rule for copying (docs/library.md).
install(FILES ${PROJECT_SOURCE_DIR}/assets/udev/70-contactlab.rules DESTINATION lib/udev/rules.d)
# The guide keeps its relative links: README.md beside docs/ and scenes/README.md.
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CONTACTLAB_DOC_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs DESTINATION ${CONTACTLAB_DOC_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/scenes/README.md DESTINATION ${CONTACTLAB_DOC_DIR}/scenes)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples DESTINATION ${CONTACTLAB_DOC_DIR})
