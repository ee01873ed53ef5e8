#pragma once
// The signature's loops are compiled twice on x86-64, for AVX2 and for the baseline, and one
// is picked at load time (GCC's and Clang's target_clones, an ifunc): no -march flag. Neither
// target has FMA to fuse a·b + c with (AVX2 does not imply it), and the loops use the same
// vector type or work element by element, so both clones give the same floats: a map made on
// one machine compares exactly with a query made on another. One loop is written with AVX2
// intrinsics instead, picked at run time by a CPU check: the luminance of BGR pixels
// (panorama_lines.cpp), integer arithmetic that gives the portable loop's values exactly.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define OMNINAV_KERNEL_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define OMNINAV_KERNEL_CLONES
#endif
