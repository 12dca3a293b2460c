// Shared by mesh.frag and ground.frag: sun with a PCF shadow map, hemisphere ambient, specular,
// distance fog to the horizon colour, and the conversion to display (sRGB) values.
// Colours arrive in sRGB (as people pick them) and are lit in linear space.

uniform vec3 uSunDirection;     // unit vector toward the sun
uniform vec3 uSunColour;        // linear
uniform vec3 uSkyAmbient;       // linear, light from above
uniform vec3 uGroundAmbient;    // linear, light bounced from below
uniform vec3 uHorizonColour;    // linear, what fog fades to
uniform vec3 uCameraPosition;
uniform float uFogDistance;     // distance at which fog reaches 63 %
uniform mat4 uLightViewProjection;
uniform sampler2DShadow uShadowMap;
uniform float uShadowTexel;     // 1 / shadow map size
uniform float uShadowNormalOffset;  // world units, against acne on grazing surfaces
uniform int uShadowFilter;      // 0: 4 x 4 PCF (headless, full quality); 1: one tap; 2: no shadows

vec3 toLinear(vec3 srgb) { return pow(srgb, vec3(2.2)); }

vec3 toDisplay(vec3 linear) {
    // A gentle shoulder keeps highlights from clipping flat.
    linear = linear / (1.0 + 0.12 * linear);
    return pow(clamp(linear, 0.0, 1.0), vec3(1.0 / 2.2));
}

float sunVisibility(vec3 worldPosition, vec3 normal) {
    vec3 offsetPosition = worldPosition + normal * uShadowNormalOffset;
    vec4 lightSpace = uLightViewProjection * vec4(offsetPosition, 1.0);
    vec3 p = lightSpace.xyz / lightSpace.w * 0.5 + 0.5;
    if (p.z >= 1.0 || uShadowFilter == 2) return 1.0;
    // The light quality level (software rasterisers): one bilinear tap, a sixteenth of the work.
    if (uShadowFilter == 1) return texture(uShadowMap, vec3(p.xy, p.z - 0.0005));
    // 4 x 4 percentage-closer filter (each tap is itself bilinear-filtered).
    float lit = 0.0;
    for (int x = 0; x < 4; ++x) {
        for (int y = 0; y < 4; ++y) {
            vec2 offset = (vec2(x, y) - 1.5) * uShadowTexel;
            lit += texture(uShadowMap, vec3(p.xy + offset, p.z - 0.0005));
        }
    }
    return lit / 16.0;
}

vec3 shade(vec3 albedo, vec3 normal, vec3 worldPosition, float specularStrength) {
    vec3 viewDirection = normalize(uCameraPosition - worldPosition);
    // Faces seen from behind (open meshes) are lit as their front.
    if (dot(normal, viewDirection) < 0.0) normal = -normal;
    float sunCosine = max(dot(normal, uSunDirection), 0.0);
    float visibility = sunCosine > 0.0 ? sunVisibility(worldPosition, normal) : 0.0;
    vec3 halfway = normalize(uSunDirection + viewDirection);
    float specular = pow(max(dot(normal, halfway), 0.0), 64.0) * specularStrength * sunCosine;
    vec3 ambient = mix(uGroundAmbient, uSkyAmbient, normal.y * 0.5 + 0.5);
    vec3 colour = albedo * (ambient + uSunColour * sunCosine * visibility) +
                  uSunColour * specular * visibility;
    float distance = length(worldPosition - uCameraPosition);
    float fog = 1.0 - exp(-(distance * distance) / (uFogDistance * uFogDistance));
    return mix(colour, uHorizonColour, fog);
}
