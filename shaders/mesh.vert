// Instanced shapes: one unit (or per-size) mesh, a model matrix and a colour per instance.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in mat4 aModel;  // locations 2 to 5
layout(location = 6) in vec4 aColour;

uniform mat4 uViewProjection;

out vec3 vWorldPosition;
out vec3 vNormal;
out vec4 vColour;

void main() {
    vec4 world = aModel * vec4(aPosition, 1.0);
    // Boxes scale unevenly: normals need the inverse transpose.
    vNormal = transpose(inverse(mat3(aModel))) * aNormal;
    vWorldPosition = world.xyz;
    vColour = aColour;
    gl_Position = uViewProjection * world;
}
