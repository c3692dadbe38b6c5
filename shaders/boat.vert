// Floating bodies (globe/render/Boats): a hull mesh in body axes placed at
// its pose. The pose's offset from the eye is made in double on the CPU, so
// a boat stays precise at 1 m from the camera.
layout(location = 0) in vec3 aBody;  // vertex in body axes, m

uniform mat4 uViewProj;  // rotation-only view (eye at the origin) and projection
uniform mat3 uRot;       // body -> ECEF
uniform vec3 uOffset;    // centre of mass - eye, ECEF, m
uniform vec4 uClipPlane; // mirrored pass: keep dot(p, xyz) + w >= 0 (above the sea plane)

out vec3 vEyeRel;

void main() {
  vec3 p = uOffset + uRot * aBody;
  vEyeRel = p;
  gl_ClipDistance[0] = dot(p, uClipPlane.xyz) + uClipPlane.w;
  gl_Position = uViewProj * vec4(p, 1.0);
}
