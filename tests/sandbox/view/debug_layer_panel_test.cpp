// sandbox/view/debug_layer_panel.cpp: the B, M and V keys toggle the bodies' debug layers, an
// odd number of presses in a frame once and an even number not at all, and leave the others.

#include "view/debug_layer_panel.h"

#include <gtest/gtest.h>

namespace substep::view {
namespace {

TEST(DebugLayerPanelTest, KeysToggleTheirOwnLayerOnAnOddCount) {
    DrawingOptions drawing;
    const DrawingOptions defaults;
    EXPECT_FALSE(defaults.bounds || defaults.centresOfMass || defaults.velocities) << "off by default";
    EXPECT_FALSE(toggleLayersByKey(KeyActions{}, drawing));
    EXPECT_TRUE(toggleLayersByKey(KeyActions{.toggleBounds = 1, .toggleVelocities = 2}, drawing));
    EXPECT_TRUE(drawing.bounds);
    EXPECT_FALSE(drawing.velocities);
    EXPECT_FALSE(drawing.centresOfMass);
    EXPECT_TRUE(toggleLayersByKey(KeyActions{.toggleBounds = 3, .toggleCentresOfMass = 1}, drawing));
    EXPECT_FALSE(drawing.bounds);
    EXPECT_TRUE(drawing.centresOfMass);
    // The joint and contact layers are the panel's checkboxes, untouched by these keys.
    EXPECT_EQ(drawing.jointFrames, defaults.jointFrames);
    EXPECT_EQ(drawing.contacts, defaults.contacts);
}

}  // namespace
}  // namespace substep::view
