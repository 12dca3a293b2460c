// Runs of attachments one per lane of an AVX2 register (attachment_lanes_kernel.h): rc_car's four
// rims step their chains together.
#include "physics/soft/attachment_run.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <span>

#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
#include "physics/soft/attachment_lanes_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("avx2")]] void solveAttachmentRunsInLanes(std::span<AttachmentRun> runs, Attachment* attachments,
                                                        Vec3* x, const double* invMass, double invH2) {
    runInLanes(runs, attachments, x, invMass, invH2);
}

}  // namespace substep
