# package.cmake — `cpack -G DEB` in the build folder (scripts/package): one Debian package with
# everything install.cmake lays out, under /usr.
set(CPACK_PACKAGE_NAME contactlab)
set(CPACK_PACKAGE_VENDOR "ContactLab")
set(CPACK_PACKAGE_CONTACT "ContactLab developers <contactlab@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Haptic display of contact location: a sandbox with a Vulkan editor")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "ContactLab renders contact force and the location of contact along the fingerpad (an arc finger "
  "against 2-D contours) on a decoupled servo thread, with simulated, replayed and USB devices, a "
  "headless command line and the seeds' experiments. Includes the physics core as static libraries "
  "with their CMake package (find_package(ContactLab)).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # contactlab_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries the binary links (libvulkan1, libglfw3, libusb-1.0-0, libstdc++6, ...) come
# from dpkg-shlibdeps; what it loads at run time does not: a Vulkan driver.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The binary without its debug information (the static libraries keep their symbols).
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "mesa-vulkan-drivers | vulkan-icd")
# find_package(ContactLab) needs the headers the exported targets use.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libglm-dev, nlohmann-json3-dev, libeigen3-dev, libusb-1.0-0-dev, pkg-config")
include(CPack)
