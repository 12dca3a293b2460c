// Tests engine/ecs/view.h: views over one, two and three component types, their deterministic
// order, and the iteration rule (removing from or destroying the current entity mid-walk).

#include "ecs/view.h"
#include "ecs/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

namespace substep::ecs {
namespace {

struct A {
    int value = 0;
};
struct B {
    int value = 0;
};
struct C {
    int value = 0;
};
struct Unused {};

/// 30 entities: every one has A, every second B, every third C; component values = entity order.
struct Fixture {
    Registry registry;
    std::vector<Entity> entities;
    Fixture() {
        for (int i = 0; i < 30; ++i) {
            const Entity e = registry.create();
            entities.push_back(e);
            registry.emplace<A>(e, i);
            if (i % 2 == 0) registry.emplace<B>(e, i);
            if (i % 3 == 0) registry.emplace<C>(e, i);
        }
    }
};

template <class... Ts>
std::vector<int> visitedValues(Registry& registry) {
    std::vector<int> values;
    registry.view<Ts...>().each([&](Entity, Ts&... components) {
        const int first = std::get<0>(std::tie(components...)).value;
        EXPECT_TRUE(((components.value == first) && ...));
        values.push_back(first);
    });
    return values;
}

TEST(View, OverOneTypeVisitsEveryOwnerInReverseDenseOrder) {
    Fixture f;
    std::vector<int> expected(30);
    for (int i = 0; i < 30; ++i)
        expected[i] = 29 - i;
    EXPECT_EQ(visitedValues<A>(f.registry), expected);
}

TEST(View, OverTwoTypesVisitsOwnersOfBoth) {
    Fixture f;
    std::vector<int> expected;
    for (int i = 29; i >= 0; --i)
        if (i % 2 == 0) expected.push_back(i);
    EXPECT_EQ((visitedValues<A, B>(f.registry)), expected);
    EXPECT_EQ((visitedValues<B, A>(f.registry)), expected);
}

TEST(View, OverThreeTypesVisitsOwnersOfAll) {
    Fixture f;
    std::vector<int> expected;
    for (int i = 29; i >= 0; --i)
        if (i % 6 == 0) expected.push_back(i);
    EXPECT_EQ((visitedValues<A, B, C>(f.registry)), expected);
    EXPECT_EQ((visitedValues<C, A, B>(f.registry)), expected);
}

TEST(View, WalksTheSmallestPool) {
    Fixture f;
    EXPECT_EQ((f.registry.view<A, B, C>().sizeHint()), 10u);  // C: every third of 30
    EXPECT_EQ(f.registry.view<A>().sizeHint(), 30u);
}

TEST(View, WithANeverUsedTypeIsEmpty) {
    Fixture f;
    int visits = 0;
    f.registry.view<A, Unused>().each([&](A&, Unused&) { ++visits; });
    for (Entity e : f.registry.view<Unused, A>()) {
        (void)e;
        ++visits;
    }
    EXPECT_EQ(visits, 0);
}

TEST(View, CallbackMayOmitTheEntity) {
    Fixture f;
    int sum = 0;
    f.registry.view<A, C>().each([&](A& a, C&) { sum += a.value; });
    EXPECT_EQ(sum, 0 + 3 + 6 + 9 + 12 + 15 + 18 + 21 + 24 + 27);
}

TEST(View, RangeForMatchesEach) {
    Fixture f;
    std::vector<Entity> fromEach;
    f.registry.view<A, B>().each([&](Entity e, A&, B&) { fromEach.push_back(e); });
    std::vector<Entity> fromLoop;
    auto view = f.registry.view<A, B>();
    for (Entity e : view) {
        EXPECT_EQ(view.get<A>(e).value, view.get<B>(e).value);
        fromLoop.push_back(e);
    }
    EXPECT_EQ(fromEach, fromLoop);
}

TEST(View, OrderIsReproducibleAfterRemovals) {
    // Two registries given the same operations walk in the same order.
    auto run = [] {
        Fixture f;
        for (int i = 0; i < 30; i += 4)
            f.registry.remove<A>(f.entities[i]);
        f.registry.destroy(f.entities[7]);
        f.registry.emplace<A>(f.registry.create(), 100);
        return visitedValues<A>(f.registry);
    };
    EXPECT_EQ(run(), run());
}

TEST(View, RemovingTheCurrentEntitysComponentVisitsEveryOtherOnce) {
    for (int removeEvery : {1, 2, 3}) {
        Fixture f;
        std::map<int, int> visits;
        f.registry.view<A, B>().each([&](Entity e, A& a, B&) {
            ++visits[a.value];
            // Removing the walked pool's component (A, the larger, is not walked; B is).
            if (a.value % removeEvery == 0) f.registry.remove<B>(e);
            if (a.value % (removeEvery + 1) == 0) f.registry.remove<A>(e);
        });
        EXPECT_EQ(visits.size(), 15u) << removeEvery;
        for (const auto& [value, count] : visits)
            EXPECT_EQ(count, 1) << value;
    }
}

TEST(View, DestroyingTheCurrentEntityVisitsEveryOtherOnce) {
    Fixture f;
    std::map<int, int> visits;
    f.registry.view<A>().each([&](Entity e, A& a) {
        ++visits[a.value];
        if (a.value % 3 != 1) f.registry.destroy(e);
    });
    EXPECT_EQ(visits.size(), 30u);
    for (const auto& [value, count] : visits)
        EXPECT_EQ(count, 1) << value;
    EXPECT_EQ(f.registry.aliveCount(), 10u);

    // The survivors are intact.
    std::vector<int> left = visitedValues<A>(f.registry);
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<int>{1, 4, 7, 10, 13, 16, 19, 22, 25, 28}));
}

TEST(View, DestroyingInARangeForVisitsEveryOtherOnce) {
    Fixture f;
    std::map<int, int> visits;
    for (Entity e : f.registry.view<A, C>()) {
        ++visits[f.registry.get<A>(e).value];
        f.registry.destroy(e);
    }
    EXPECT_EQ(visits.size(), 10u);
    for (const auto& [value, count] : visits)
        EXPECT_EQ(count, 1) << value;
    EXPECT_EQ(f.registry.pool<C>().size(), 0u);
}

TEST(View, EntitiesAddedDuringTheWalkAreNotVisited) {
    Fixture f;
    int visits = 0;
    f.registry.view<A>().each([&](A&) {
        ++visits;
        f.registry.emplace<A>(f.registry.create(), -1);
    });
    EXPECT_EQ(visits, 30);
    EXPECT_EQ(f.registry.pool<A>().size(), 60u);
}

}  // namespace
}  // namespace substep::ecs
