#pragma once
/// What the `substep` commands (run, bench, sweep) share between option parsing and their frame
/// loops: numbers typed as text checked against their accepted range, with messages that name the
/// option, and the Ctrl-C/SIGTERM guard that lets a long loop stop cleanly so its temporary
/// outputs (AtomicFile) are removed.

#include "physics/correction.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace substep {

class World;

/// A bad option value; what() names the option. The commands report it and exit 2.
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Runs a command's `body` and returns its exit code. Everything it throws is bad input
/// (UsageError, UnknownSceneError, SceneError) or an output that cannot be written (OutputError),
/// each message naming its option or file: printed as "substep COMMAND: message", exit code 2.
/// The temporary outputs are gone by then (AtomicFile's destructor).
int runReportingErrors(const char* command, const std::function<int()>& body);

/// `text` as a whole number in [lowest, highest]. Throws UsageError naming `option` when it is
/// not a whole number or is out of range (a value too large for long long counts as out of range).
long long parseInteger(const char* option, std::string_view text, long long lowest,
                       long long highest);

/// `text` as a positive finite number. Throws UsageError naming `option` otherwise.
double parsePositiveReal(const char* option, const std::string& text);

/// `text` as a positive finite number no larger than `highest` (a whole number, as the message
/// prints it). Throws UsageError naming `option` otherwise.
double parsePositiveReal(const char* option, const std::string& text, double highest);

/// Most threads `--threads` accepts (a sanity bound).
inline constexpr long long kMaxThreads = 64;

/// `--threads N` (run, bench, sweep; DESIGN.md): 1 when `text` is empty, else a whole number in
/// [1, kMaxThreads]. Throws UsageError naming --threads otherwise.
int parseThreads(const std::string& text);
/// `text` as a joint projection ("paper" or "start", WorldSettings::jointProjection). Throws
/// UsageError naming `option` otherwise.
JointProjection parseJointProjection(const char* option, const std::string& text);
/// `text` as a restitution rule: "swept" (true: WorldSettings::sweptRestitution, the sweeps of
/// two-body collisions) or "paper" (false: Eq. 34 alone). Throws UsageError naming `option`
/// otherwise.
bool parseSweptRestitution(const char* option, const std::string& text);
/// `text` as a finite number in [lowest, highest]. Throws UsageError naming `option` otherwise.
double parseRealWithin(const char* option, const std::string& text, double lowest, double highest);

/// round(seconds / dt) frames, the simulated time T as frames (DESIGN.md). Throws UsageError
/// naming --seconds when that is more than `maxFrames`.
long long framesForSeconds(double seconds, double dt, long long maxFrames);

/// Prints one warning per process the first time a step dropped contact pairs over the per-frame
/// cap (World::droppedContactPairs): the run goes on, with less contact than the scene asks for.
void warnAboutDroppedContacts(const char* command, const World& world, long long frame);

/// The signal (SIGINT or SIGTERM) received since the current InterruptGuard was made; 0 if none.
/// Frame loops poll it and stop, so the outputs' destructors remove the temporary files.
int interruptSignal();

/// Catches SIGINT and SIGTERM while alive (interruptSignal() reports them) instead of letting
/// them kill the program with temporary files left behind; restores the previous handlers.
class InterruptGuard {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

  private:
    void (*previousInt_)(int) = nullptr;
    void (*previousTerm_)(int) = nullptr;
};

}  // namespace substep
