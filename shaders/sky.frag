// Sky gradient from the horizon to the zenith, darker below the horizon, a soft glow around the
// sun. A fixed ordered dither (from the pixel position only, so frames stay reproducible)
// hides the 8-bit banding of the slow gradient.
in vec2 vNdc;

uniform mat4 uInverseViewProjection;
uniform vec3 uSkyZenith;      // sRGB
uniform vec3 uSkyHorizon;     // sRGB
uniform vec3 uSunDirection;

out vec4 fragColour;

void main() {
    vec4 nearPoint = uInverseViewProjection * vec4(vNdc, -1.0, 1.0);
    vec4 farPoint = uInverseViewProjection * vec4(vNdc, 1.0, 1.0);
    vec3 direction = normalize(farPoint.xyz / farPoint.w - nearPoint.xyz / nearPoint.w);
    float height = direction.y;
    vec3 colour = mix(uSkyHorizon, uSkyZenith, pow(clamp(height, 0.0, 1.0), 0.5));
    if (height < 0.0) colour = mix(uSkyHorizon, uSkyHorizon * 0.8, clamp(-height * 3.0, 0.0, 1.0));
    float sunGlow = pow(max(dot(direction, uSunDirection), 0.0), 24.0);
    colour += vec3(1.0, 0.9, 0.7) * sunGlow * 0.25;
    ivec2 pixel = ivec2(gl_FragCoord.xy) & 3;
    int bayer[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
    float dither = (float(bayer[pixel.y * 4 + pixel.x]) + 0.5) / 16.0 - 0.5;
    fragColour = vec4(colour + dither / 255.0, 1.0);
}
