// Trivial fragment shader: the reference draw for frame-time ratios.
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(0.5, 0.5, 0.5, 1.0); }
