// Tests engine/ecs/registry.h (with sparse_set.h and component_pool.h): entities with index
// reuse and generations, components added, read, replaced and removed, and the reference
// stability rule of component_pool.h.

#include "ecs/registry.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace substep::ecs {
namespace {

struct Position {
    double x = 0.0;
};
struct Label {
    std::string text;
};
/// A non-aggregate component, built with parentheses.
class Counter {
  public:
    explicit Counter(int start) : value_(start) {}
    int value() const { return value_; }

  private:
    int value_;
};

TEST(Registry, NullEntityIsNeverValid) {
    Registry registry;
    EXPECT_TRUE(Entity{}.isNull());
    EXPECT_FALSE(registry.isValid(Entity{}));
    EXPECT_FALSE(registry.isValid(kNullEntity));
    const Entity e = registry.create();
    EXPECT_FALSE(e.isNull());
    EXPECT_FALSE(registry.isValid({e.index, 0}));
}

TEST(Registry, DestroyedSlotIsReusedWithANewGeneration) {
    Registry registry;
    const Entity a = registry.create();
    const Entity b = registry.create();
    EXPECT_NE(a.index, b.index);
    EXPECT_EQ(registry.aliveCount(), 2u);

    registry.destroy(a);
    EXPECT_FALSE(registry.isValid(a));
    EXPECT_TRUE(registry.isValid(b));
    EXPECT_EQ(registry.aliveCount(), 1u);

    const Entity c = registry.create();
    EXPECT_EQ(c.index, a.index);
    EXPECT_EQ(c.generation, a.generation + 1);
    EXPECT_TRUE(registry.isValid(c));
    EXPECT_FALSE(registry.isValid(a));  // the stale handle stays invalid
    EXPECT_NE(a, c);

    // Destroying through a stale handle does nothing to the slot's new occupant.
    registry.destroy(a);
    EXPECT_TRUE(registry.isValid(c));
    EXPECT_EQ(registry.aliveCount(), 2u);
}

TEST(Registry, SlotsAreReusedLastFreedFirst) {
    Registry registry;
    const Entity a = registry.create();
    const Entity b = registry.create();
    registry.destroy(a);
    registry.destroy(b);
    EXPECT_EQ(registry.create().index, b.index);
    EXPECT_EQ(registry.create().index, a.index);
    EXPECT_EQ(registry.create().index, 2u);
}

TEST(Registry, ComponentsAreAddedReadAndRemoved) {
    Registry registry;
    const Entity e = registry.create();
    EXPECT_FALSE(registry.has<Position>(e));
    EXPECT_EQ(registry.tryGet<Position>(e), nullptr);

    registry.emplace<Position>(e, 1.5);
    registry.emplace<Label>(e, "crate");
    registry.emplace<Counter>(e, 7);
    EXPECT_TRUE(registry.has<Position>(e));
    EXPECT_EQ(registry.get<Position>(e).x, 1.5);
    EXPECT_EQ(registry.get<Label>(e).text, "crate");
    EXPECT_EQ(registry.get<Counter>(e).value(), 7);
    ASSERT_NE(registry.tryGet<Label>(e), nullptr);

    const Registry& constRegistry = registry;
    EXPECT_EQ(constRegistry.get<Position>(e).x, 1.5);
    EXPECT_NE(constRegistry.tryGet<Label>(e), nullptr);

    EXPECT_TRUE(registry.remove<Label>(e));
    EXPECT_FALSE(registry.remove<Label>(e));
    EXPECT_FALSE(registry.has<Label>(e));
    EXPECT_TRUE(registry.has<Position>(e));
}

TEST(Registry, EmplacingAgainReplacesTheComponent) {
    Registry registry;
    const Entity e = registry.create();
    registry.emplace<Position>(e, 1.0);
    registry.emplace<Position>(e, 2.0);
    EXPECT_EQ(registry.get<Position>(e).x, 2.0);
    EXPECT_EQ(registry.pool<Position>().size(), 1u);
}

TEST(Registry, EmplaceOnAnInvalidEntityThrows) {
    Registry registry;
    const Entity e = registry.create();
    registry.destroy(e);
    EXPECT_THROW(registry.emplace<Position>(e, 1.0), std::invalid_argument);
    EXPECT_THROW(registry.emplace<Position>(Entity{}, 1.0), std::invalid_argument);
}

TEST(Registry, DestroyRemovesEveryComponent) {
    Registry registry;
    const Entity e = registry.create();
    registry.emplace<Position>(e, 1.0);
    registry.emplace<Label>(e, "gone");
    registry.destroy(e);
    EXPECT_EQ(registry.pool<Position>().size(), 0u);
    EXPECT_EQ(registry.pool<Label>().size(), 0u);

    // The slot's next occupant starts without components.
    const Entity reused = registry.create();
    ASSERT_EQ(reused.index, e.index);
    EXPECT_FALSE(registry.has<Position>(reused));
    EXPECT_FALSE(registry.has<Position>(e));
}

TEST(Registry, StaleHandleDoesNotSeeTheNewOccupantsComponents) {
    Registry registry;
    const Entity old = registry.create();
    registry.destroy(old);
    const Entity reused = registry.create();
    registry.emplace<Position>(reused, 3.0);
    EXPECT_FALSE(registry.has<Position>(old));
    EXPECT_EQ(registry.tryGet<Position>(old), nullptr);
    EXPECT_FALSE(registry.remove<Position>(old));
    EXPECT_TRUE(registry.has<Position>(reused));
}

TEST(Registry, ManyEntitiesKeepTheirOwnComponents) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 10000; ++i) {
        const Entity e = registry.create();
        entities.push_back(e);
        registry.emplace<Position>(e, double(i));
        if (i % 3 == 0) registry.emplace<Label>(e, std::to_string(i));
    }
    // Remove every other Position (swap-and-pop shuffles the dense arrays) and destroy some.
    for (int i = 0; i < 10000; i += 2)
        registry.remove<Position>(entities[i]);
    for (int i = 0; i < 10000; i += 5)
        registry.destroy(entities[i]);

    for (int i = 0; i < 10000; ++i) {
        const Entity e = entities[i];
        const bool alive = i % 5 != 0;
        ASSERT_EQ(registry.isValid(e), alive) << i;
        ASSERT_EQ(registry.has<Position>(e), alive && i % 2 == 1) << i;
        if (registry.has<Position>(e)) {
            ASSERT_EQ(registry.get<Position>(e).x, double(i));
        }
        ASSERT_EQ(registry.has<Label>(e), alive && i % 3 == 0) << i;
        if (registry.has<Label>(e)) {
            ASSERT_EQ(registry.get<Label>(e).text, std::to_string(i));
        }
    }
    // The pools' dense arrays stay parallel to their entity arrays.
    const ComponentPool<Position>& positions = registry.pool<Position>();
    for (std::size_t k = 0; k < positions.size(); ++k)
        ASSERT_EQ(positions.components()[k].x, double(positions.entities()[k].index));
}

TEST(Registry, ReferencesSurviveWorkOnOtherPools) {
    Registry registry;
    const Entity e = registry.create();
    Position& position = registry.emplace<Position>(e, 4.0);
    for (int i = 0; i < 1000; ++i) {
        const Entity other = registry.create();
        registry.emplace<Label>(other, "x");
        if (i % 2 == 0) registry.destroy(other);
    }
    EXPECT_EQ(&position, &registry.get<Position>(e));
    EXPECT_EQ(position.x, 4.0);
}

TEST(Registry, ReservedPoolKeepsReferencesAcrossInsertions) {
    Registry registry;
    registry.pool<Position>().reserve(100);
    const Entity first = registry.create();
    Position& position = registry.emplace<Position>(first, 1.0);
    for (int i = 0; i < 99; ++i)
        registry.emplace<Position>(registry.create(), 0.0);
    EXPECT_EQ(&position, &registry.get<Position>(first));
}

TEST(Registry, RemovalMovesOnlyTheLastComponent) {
    Registry registry;
    const Entity a = registry.create();
    const Entity b = registry.create();
    const Entity c = registry.create();
    registry.emplace<Position>(a, 1.0);
    registry.emplace<Position>(b, 2.0);
    registry.emplace<Position>(c, 3.0);
    const Position& pa = registry.get<Position>(a);  // taken after the insertions
    const Position* pc = &registry.get<Position>(c);
    registry.remove<Position>(b);
    // a's component did not move; c's moved into b's place (its old address is not its own).
    EXPECT_EQ(&pa, &registry.get<Position>(a));
    EXPECT_NE(pc, &registry.get<Position>(c));
    EXPECT_EQ(registry.get<Position>(c).x, 3.0);
}

TEST(Registry, MovedRegistryKeepsEntitiesAndComponents) {
    Registry registry;
    const Entity e = registry.create();
    Position* position = &registry.emplace<Position>(e, 5.0);
    Registry moved = std::move(registry);
    EXPECT_TRUE(moved.isValid(e));
    EXPECT_EQ(&moved.get<Position>(e), position);  // pools live on the heap
}

TEST(ComponentTypeId, IsOnePerUnqualifiedType) {
    EXPECT_EQ(componentTypeId<Position>(), componentTypeId<const Position>());
    EXPECT_EQ(componentTypeId<Position>(), componentTypeId<Position&>());
    EXPECT_NE(componentTypeId<Position>(), componentTypeId<Label>());
}

}  // namespace
}  // namespace substep::ecs
