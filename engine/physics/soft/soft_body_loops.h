#pragma once
/// SoftSystem's loops over its bodies, with or without a worker pool (soft_system.h declares
/// them): the soft system's files that run stages body by body include this one.

#include "physics/soft/soft_system.h"
#include "physics/worker_pool.h"

namespace substep {

template <class Visit>
void SoftSystem::forEachBody(WorkerPool* pool, Visit&& visit) {
    if (!pool || liveBodies_ < 2) {
        for (SoftBodyData& body : bodies_)
            if (body.alive) visit(body);
        return;
    }
    pool->parallelFor(static_cast<int>(bodies_.size()), [&](int index) {
        SoftBodyData& body = bodies_[static_cast<size_t>(index)];
        if (body.alive) visit(body);
    });
}

template <class Visit>
void SoftSystem::forEachBodyBatches(WorkerPool* pool, Visit&& visit) {
    if (!pool || bodyBatches_.size() < 2) {
        visit(0, static_cast<uint32_t>(batches_.size()));
        return;
    }
    pool->parallelFor(static_cast<int>(bodyBatches_.size()), [&](int block) {
        const auto [first, end] = bodyBatches_[static_cast<size_t>(block)];
        visit(first, end);
    });
}

}  // namespace substep
