in vec3 vColour;

uniform float uOpacity;  // lines behind surfaces are drawn faintly, the rest fully

out vec4 fragColour;

void main() {
    fragColour = vec4(vColour, uOpacity);
}
