// Sine, cosine and arctangent that give the same bits on every machine.
//
// The C library's versions are chosen when the program starts by what the processor can do:
// glibc runs one build of sin, cos and atan2 on processors with fused multiply–add and another on
// those without, and the two differ in the last bit for some arguments. A joint's angle or a
// Lua scene's terrain computed with them then steps to other bits on another machine (measured:
// six of the golden-hash scenes changed when glibc was told to use its other build). These
// functions use only + − × ÷ and √, which IEEE 754 rounds the same everywhere, in a fixed order
// (the project compiles with -ffp-contract=off, so no multiply–add is fused behind their back).
//
// Accuracy: within about one unit in the last place of the true value for |x| ≤ 8·10⁵ rad (the
// reduction by π/2 uses π/2 split into three parts, exact for these arguments); above that, the
// argument is first reduced by 2π with fmod (exact, but by the double nearest 2π, so the error
// grows with |x|: about |x|·2⁻⁵³ rad). docs/physics.md, "Same bits on every machine".
#pragma once

namespace rigidlab {

double portableSin(double x);
double portableCos(double x);
void portableSinCos(double x, double& s, double& c);  // both, with one reduction
double portableAtan(double x);
double portableAtan2(double y, double x);  // the quadrant and special cases of C's atan2

}  // namespace rigidlab
