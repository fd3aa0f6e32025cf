#version 450
// The stencil pass writes no colour: only the stencil operations do anything. An empty
// fragment shader is the cheapest one there is.
void main() {}
