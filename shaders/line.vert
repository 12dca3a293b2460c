// Debug lines (joint frames, forces): world-space endpoints with a colour each.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColour;

uniform mat4 uViewProjection;

out vec3 vColour;

void main() {
    vColour = aColour;
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
