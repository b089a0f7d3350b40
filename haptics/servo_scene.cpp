// servo_scene.cpp — building a servo-ready scene and swapping it in by pointer.
#include "haptics/servo_scene.hpp"

namespace contactlab {

ServoScene::ServoScene(const Scene& s) : scene(s), env(build_environment(s)), proxy(env, proxy_def_of(s)) {}

SceneExchange::~SceneExchange() {
    delete pending_.exchange(nullptr);
    delete retired_.exchange(nullptr);
}

void SceneExchange::publish(std::unique_ptr<ServoScene> s) {
    reclaim();
    delete pending_.exchange(s.release(), std::memory_order_acq_rel);
}

void SceneExchange::reclaim() { delete retired_.exchange(nullptr, std::memory_order_acq_rel); }

ServoScene* SceneExchange::take(ServoScene* current) noexcept {
    // Only swap when the old scene has somewhere to go: the servo must never delete it itself.
    if (retired_.load(std::memory_order_acquire) != nullptr) return nullptr;
    ServoScene* next = pending_.exchange(nullptr, std::memory_order_acq_rel);
    if (next == nullptr) return nullptr;
    retired_.store(current, std::memory_order_release);
    return next;
}

}  // namespace contactlab
