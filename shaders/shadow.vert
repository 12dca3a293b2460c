// Depth from the sun for the shadow map; same instance layout as mesh.vert.
layout(location = 0) in vec3 aPosition;
layout(location = 2) in mat4 aModel;

uniform mat4 uLightViewProjection;

void main() {
    gl_Position = uLightViewProjection * aModel * vec4(aPosition, 1.0);
}
