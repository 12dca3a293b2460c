// A full-screen triangle at the far plane; the fragment shader finds each pixel's view ray.
out vec2 vNdc;

void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    vNdc = corner * 2.0 - 1.0;
    gl_Position = vec4(vNdc, 1.0, 1.0);
}
