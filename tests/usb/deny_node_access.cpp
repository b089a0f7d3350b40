// deny_node_access.cpp — see deny_node_access.hpp.
#include "deny_node_access.hpp"

#include <linux/capability.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace usb_test {

void deny_node_access(UMockdevTestbed* testbed, const std::string& node) {
    gchar* root = umockdev_testbed_get_root_dir(testbed);
    const std::string file = std::string(root) + node;
    g_free(root);
    ::chmod(file.c_str(), 0);
    if (::geteuid() == 0) {
        // Root ignores file modes through CAP_DAC_OVERRIDE: drop it (and DAC_READ_SEARCH) from
        // the effective set so this process meets the node the way an ordinary user does.
        __user_cap_header_struct hdr{_LINUX_CAPABILITY_VERSION_3, 0};
        __user_cap_data_struct data[2]{};
        syscall(SYS_capget, &hdr, data);
        data[0].effective &= ~((1u << CAP_DAC_OVERRIDE) | (1u << CAP_DAC_READ_SEARCH));
        syscall(SYS_capset, &hdr, data);
        // And from the bounding set, so that programs this test starts (which regain every
        // capability in it when root executes them) meet the node the same way.
        ::prctl(PR_CAPBSET_DROP, CAP_DAC_OVERRIDE, 0, 0, 0);
        ::prctl(PR_CAPBSET_DROP, CAP_DAC_READ_SEARCH, 0, 0, 0);
    }
}

}  // namespace usb_test
