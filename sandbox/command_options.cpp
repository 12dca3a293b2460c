#include "command_options.h"

#include "atomic_file.h"

#include "physics/joint_projection.h"
#include "physics/step_cancellation.h"
#include "physics/world.h"

#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>

namespace substep {

namespace {

/// `text` as a number, or UsageError when it is not one (or does not fit a double).
double parseReal(const char* option, const std::string& text) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [last, error] = std::from_chars(text.data(), end, value);
    if (error == std::errc::result_out_of_range) {
        throw UsageError(std::string(option) + ": " + text + " is out of range");
    }
    if (error != std::errc() || last != end || text.empty()) {
        throw UsageError(std::string(option) + ": expected a number, got '" + text + "'");
    }
    return value;
}

// Set by the signal handler, read by the frame loops: a sig_atomic_t is all a handler may write.
volatile std::sig_atomic_t gInterrupted = 0;

extern "C" void onInterrupt(int signal) {
    gInterrupted = signal;
    // A frame may take minutes: the world's step returns at its next substep.
    requestStepCancellation();
}

}  // namespace

int runReportingErrors(const char* command, const std::function<int()>& body) {
    try {
        return body();
    } catch (const std::exception& error) {
        // One line whatever it names: a file name's newline or escape is shown escaped.
        std::fprintf(stderr, "substep %s: %s\n", command, printableName(error.what()).c_str());
        return 2;
    }
}

long long parseInteger(const char* option, std::string_view text, long long lowest,
                       long long highest) {
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [last, error] = std::from_chars(text.data(), end, value);
    // Too large either way is reported as out of range, not as "not a whole number".
    if (error == std::errc::result_out_of_range)
        value = text.front() == '-' ? lowest - 1 : highest + 1;
    else if (error != std::errc() || last != end || text.empty()) {
        throw UsageError(std::string(option) + ": expected a whole number, got '" +
                         std::string(text) + "'");
    }
    if (value < lowest || value > highest) {
        throw UsageError(std::string(option) + " must be between " + std::to_string(lowest) +
                         " and " + std::to_string(highest) + ", got " + std::string(text));
    }
    return value;
}

double parsePositiveReal(const char* option, const std::string& text) {
    const double value = parseReal(option, text);
    if (!std::isfinite(value) || value <= 0.0) {
        throw UsageError(std::string(option) + " must be positive and finite, got " + text);
    }
    return value;
}

double parsePositiveReal(const char* option, const std::string& text, double highest) {
    const double value = parseReal(option, text);
    if (!std::isfinite(value) || value <= 0.0 || value > highest) {
        throw UsageError(std::string(option) + " must be positive, finite and at most " +
                         std::to_string(static_cast<long long>(highest)) + ", got " + text);
    }
    return value;
}

int parseThreads(const std::string& text) {
    return text.empty() ? 1 : static_cast<int>(parseInteger("--threads", text, 1, kMaxThreads));
}

double parseRealWithin(const char* option, const std::string& text, double lowest, double highest) {
    const double value = parseReal(option, text);
    if (!(value >= lowest && value <= highest)) {
        char bounds[96];
        std::snprintf(bounds, sizeof bounds, " must be between %g and %g, got ", lowest, highest);
        throw UsageError(std::string(option) + bounds + text);
    }
    return value;
}

long long framesForSeconds(double seconds, double dt, long long maxFrames) {
    const double frames = std::round(seconds / dt);
    // Written so that a NaN or infinite quotient fails too.
    if (!(frames <= static_cast<double>(maxFrames))) {
        throw UsageError("--seconds: T/dt is more than " + std::to_string(maxFrames) + " frames");
    }
    return static_cast<long long>(frames);
}

void warnAboutDroppedContacts(const char* command, const World& world, long long frame) {
    static bool warned = false;
    if (warned || world.droppedContactPairs() == 0) return;
    warned = true;
    std::fprintf(stderr,
                 "substep %s: warning: frame %lld found more than %zu contact pairs; %zu dropped "
                 "(bodies piled at one point?)\n",
                 command, frame, world.contactPairCap(), world.droppedContactPairs());
}

int interruptSignal() {
    return gInterrupted;
}

InterruptGuard::InterruptGuard() {
    gInterrupted = 0;
    clearStepCancellation();
    previousInt_ = std::signal(SIGINT, onInterrupt);
    previousTerm_ = std::signal(SIGTERM, onInterrupt);
}

InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, previousInt_);
    std::signal(SIGTERM, previousTerm_);
    clearStepCancellation();  // steps made after the guard run to their end again
}

JointProjection parseJointProjection(const char* option, const std::string& text) {
    if (const auto projection = jointProjectionFromName(text)) return *projection;
    throw UsageError(std::string(option) + ": expected paper or start, got '" + text + "'");
}

bool parseSweptRestitution(const char* option, const std::string& text) {
    if (text == "swept") return true;
    if (text == "paper") return false;
    throw UsageError(std::string(option) + ": expected swept or paper, got '" + text + "'");
}

}  // namespace substep
