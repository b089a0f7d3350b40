// x_server_affinity.hpp — keeps a local Xvfb off the servo's core.
//
// Why: under Xvfb with the CPU Vulkan driver, every presented frame (3.7 MB at 1280x720) reaches
// the X server through its socket, and the server's side of that copy runs in the kernel for
// milliseconds at a time. The scheduler puts Xvfb on any core, the servo's included, and a
// kernel copy is not preempted by the SCHED_FIFO servo thread on a voluntary-preemption kernel:
// that was where the editor's late servo ticks came from (`perf sched`, docs/editor.md).
// The editor's own threads (lavapipe's included) are already kept off the servo's core
// (reserve_servo_core); this does the same for the X server, when it is an Xvfb of this user on
// this machine. A desktop's X server (another user's, with a GPU doing the copy) is left alone.
#pragma once

#include <string>

namespace contactlab::editor {

// If $DISPLAY names a local X server whose process is Xvfb, removes `servo_core` from the CPU
// affinity of each of its threads. Returns what was done, for the log ("" when nothing applied).
std::string keep_x_server_off_core(int servo_core);

}  // namespace contactlab::editor
