#include "capture/capture_runner.h"

#include "capture/run_digest.h"
#include "command_options.h"

#include <algorithm>
#include <cmath>

namespace substep::capture {

namespace {

bool stateIsFinite(const CaptureState& state) {
    const auto finite = [](const auto& values) {
        return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
    };
    for (const BodyState& body : state.bodies) {
        if (!finite(body.position) || !finite(body.orientation) || !finite(body.velocity) ||
            !finite(body.angularVelocity)) {
            return false;
        }
    }
    for (const JointState& joint : state.joints) {
        if (!std::isfinite(joint.force) || !std::isfinite(joint.torque) ||
            !std::isfinite(joint.error))
            return false;
    }
    for (const SoftBodyState& soft : state.softBodies) {
        if (!finite(soft.centre) || !std::isfinite(soft.volume)) return false;
    }
    return true;
}

}  // namespace

CapturedRun runCapture(CaptureScene& scene, const CaptureSpec& spec, FrameRenderer* renderer,
                       const std::function<void(long long)>& progress) {
    CapturedRun run;
    RunDigest digest;
    CaptureState state;  // reused every frame
    std::size_t next = 0;
    for (long long frame = 0; next < spec.frames.size(); ++frame) {
        if (const int signal = interruptSignal(); signal != 0) {
            run.interrupted = signal;
            return run;
        }
        if (frame > 0) scene.step();
        progress(frame);
        if (spec.state) scene.readState(state);
        if (!scene.isFinite() || (spec.state && !stateIsFinite(state))) {
            run.nonFinite = frame;
            break;
        }
        if (spec.state) digest.add(state);
        scene.sampleMetrics();
        if (spec.frames[next] != frame) continue;

        CapturedFrame& captured = run.frames.emplace_back();
        captured.frame = frame;
        if (spec.state) captured.state = state;
        if (spec.image)
            captured.image = renderer->render(scene.draw(), spec.image->width, spec.image->height);
        ++next;
    }
    if (spec.state && !run.nonFinite) run.digest = digest.line();
    run.metrics = scene.metrics();
    return run;
}

}  // namespace substep::capture
