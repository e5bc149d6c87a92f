// Float adds from many invocations into one element of a shader storage buffer (LPV's injection
// and geometry volume). FLOAT_ATOMICS (gi/gl/extensions.h, floatAtomicsDefine) is 1 where the
// driver has GL_NV_shader_atomic_float (llvmpipe, NVIDIA): atomicAdd on the float itself
// (llvmpipe: lpv_cornell_original's injection 62 -> 9 ms, the same sums); else the element is a
// uint holding the float's bits, added by a loop on atomicCompSwap (exact under contention).
// Include it before any other code: an #extension directive must precede the shader's code.
// Declare the buffer's array with elements of type GI_ATOMIC_FLOAT and add with
// GI_ATOMIC_ADD_FLOAT(element, value).
#ifndef FLOAT_ATOMICS
#define FLOAT_ATOMICS 0
#endif
#if FLOAT_ATOMICS
#extension GL_NV_shader_atomic_float : require
#define GI_ATOMIC_FLOAT float
#define GI_ATOMIC_ADD_FLOAT(element, value) atomicAdd(element, value)
#else
#define GI_ATOMIC_FLOAT uint
#define GI_ATOMIC_ADD_FLOAT(element, value)                                                         \
    {                                                                                               \
        uint seen = element;                                                                        \
        while (true) {                                                                              \
            uint prev = atomicCompSwap(element, seen, floatBitsToUint(uintBitsToFloat(seen) + (value))); \
            if (prev == seen) break;                                                                \
            seen = prev;                                                                            \
        }                                                                                           \
    }
#endif
