// Runs of attachments one per lane of four doubles, compiled for x86-64-v4
// (attachment_lanes_kernel.h): the same lanes as attachment_lanes.cpp, with AVX-512's 32 vector
// registers, where the bodies' poses stay in registers through the links.
#include "physics/soft/attachment_run.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <span>

#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#endif
#include "physics/soft/attachment_lanes_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("arch=x86-64-v4")]] void solveAttachmentRunsInWideLanes(std::span<AttachmentRun> runs, Attachment* attachments,
                                                                      Vec3* x, const double* invMass, double invH2) {
    runInLanes(runs, attachments, x, invMass, invH2);
}

}  // namespace substep
