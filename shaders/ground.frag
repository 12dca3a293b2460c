// The ground plane with a two-level grid drawn from world coordinates (anti-aliased by the
// screen-space derivative, so lines stay one pixel wide at any distance) and shadows.
in vec3 vWorldPosition;

uniform vec3 uGroundNormal;
uniform vec3 uGroundTangent;    // grid directions on the plane
uniform vec3 uGroundBitangent;
uniform vec3 uGroundColour;     // sRGB
uniform float uGridSpacing;     // major lines; minor lines at a tenth

out vec4 fragColour;

float gridLine(vec2 coordinate) {
    vec2 width = fwidth(coordinate);
    vec2 distanceToLine = abs(fract(coordinate - 0.5) - 0.5) / max(width, vec2(1e-6));
    float line = 1.0 - min(min(distanceToLine.x, distanceToLine.y), 1.0);
    // Lines denser than a few pixels would turn into noise: fade them out.
    return line * (1.0 - smoothstep(0.15, 0.5, max(width.x, width.y)));
}

void main() {
    vec2 onPlane = vec2(dot(vWorldPosition, uGroundTangent), dot(vWorldPosition, uGroundBitangent));
    float major = gridLine(onPlane / uGridSpacing);
    float minor = gridLine(onPlane / (uGridSpacing * 0.1));
    vec3 albedo = toLinear(uGroundColour);
    albedo *= 1.0 - 0.22 * max(major, 0.4 * minor);
    vec3 colour = shade(albedo, uGroundNormal, vWorldPosition, 0.0);
    fragColour = vec4(toDisplay(colour), 1.0);
}
