#version 450
// Writes which instance covers each pixel, so error measurements compare a mesh only where
// it really covers the exact surface it stands for (used by tests and the sweep).
uniform int u_instance;
out int out_instance;
void main() { out_instance = u_instance + 1; }  // 0 stays "nothing"
