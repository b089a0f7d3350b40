// servo_scene.hpp — an immutable scene as the servo uses it, and its publication by pointer swap.
//
// A ServoScene (scene + compiled environment + a proxy with its scratch space already reserved) is
// built off the servo thread, handed over by an atomic pointer exchange at a tick boundary, and
// the one it replaced is handed back the same way for the publisher to delete: the servo thread
// never allocates or frees a scene.
#pragma once

#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

#include <atomic>
#include <memory>

namespace contactlab {

struct ServoScene {
    explicit ServoScene(const Scene& s);
    ServoScene(const ServoScene&) = delete;
    ServoScene& operator=(const ServoScene&) = delete;

    Scene scene;
    Environment env;
    Proxy proxy;  // refers to env; only the servo thread touches it once published
};

// One publisher thread, one servo thread.
class SceneExchange {
public:
    SceneExchange() = default;
    SceneExchange(const SceneExchange&) = delete;
    SceneExchange& operator=(const SceneExchange&) = delete;
    ~SceneExchange();

    // Publisher: offers a new scene. A scene offered earlier and not yet taken is deleted here
    // (the servo never saw it). Also reclaims a scene the servo has retired.
    void publish(std::unique_ptr<ServoScene> s);
    // Publisher: deletes a scene the servo has retired, if any. Call from time to time.
    void reclaim();

    // Servo: if a new scene is waiting and the retire slot is free, returns it and retires
    // `current` (which may be null); otherwise returns null and nothing changes. Wait-free.
    ServoScene* take(ServoScene* current) noexcept;

private:
    std::atomic<ServoScene*> pending_{nullptr};
    std::atomic<ServoScene*> retired_{nullptr};
};

}  // namespace contactlab
