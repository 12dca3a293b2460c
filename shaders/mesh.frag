in vec3 vWorldPosition;
in vec3 vNormal;
in vec4 vColour;

out vec4 fragColour;

void main() {
    vec3 colour = shade(toLinear(vColour.rgb), normalize(vNormal), vWorldPosition, 0.35);
    fragColour = vec4(toDisplay(colour), 1.0);
}
