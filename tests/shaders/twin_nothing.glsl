// An unused include slot of glsl_twin.comp.
