#version 460
// triangle.vert.glsl: one triangle covering the viewport (vkCmdDraw(3)), no vertex buffer; fragment passes read
// their inputs at gl_FragCoord. Ports IDKEngine's ToScreen/vertex.glsl.
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);  // (0,0) (2,0) (0,2)
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
