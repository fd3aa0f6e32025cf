#version 450
// Depth only: the rasteriser writes gl_FragCoord.z; there is no colour attachment.
void main() {}
