// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkNormalMappingMultiversioning.h
 * @brief  VTK_NORMALMAPPING_TARGET_CLONES, for the filter's vector loops (not installed).
 */
#ifndef vtkNormalMappingMultiversioning_h
#define vtkNormalMappingMultiversioning_h

/**
 * Marks a function to be compiled also for AVX2 and AVX-512 and picked by the CPU at load time
 * (function multiversioning through ifunc: GCC, and Clang from version 14, on x86-64 Linux), so
 * that each clone holds its own copy of the loops it calls: they are VTK_ALWAYS_INLINE (see
 * vtkTangentFrameKernels.h), and GCC also inlines every other call (flatten, which Clang refuses
 * on a multiversioned function). Empty for other compilers and targets, and when CMake's
 * NORMALMAPPING_MULTIVERSIONING is OFF: the function is then compiled once for the default
 * target. For the loops whose speed depends on the width of the vector unit (the weighted
 * methods' triangle and point blocks, the MikkTSpace kernel's projections); the source stays one
 * portable function. Every clone performs the same IEEE operations (no contraction into
 * fused multiply-adds: CMake/vtkNormalMappingModule.cmake), so all give the same bits.
 */
#if defined(VTK_NORMALMAPPING_NO_MULTIVERSIONING)
#define VTK_NORMALMAPPING_TARGET_CLONES
#define VTK_NORMALMAPPING_MULTIVERSIONED 0
#elif defined(__x86_64__) && defined(__linux__) && defined(__GNUC__) && !defined(__clang__)
#define VTK_NORMALMAPPING_TARGET_CLONES                                                            \
  __attribute__((target_clones("avx512f", "avx2", "default"), flatten))
#define VTK_NORMALMAPPING_MULTIVERSIONED 1
#elif defined(__x86_64__) && defined(__linux__) && defined(__clang__) && __clang_major__ >= 14
#define VTK_NORMALMAPPING_TARGET_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#define VTK_NORMALMAPPING_MULTIVERSIONED 1
#else
#define VTK_NORMALMAPPING_TARGET_CLONES
#define VTK_NORMALMAPPING_MULTIVERSIONED 0
#endif

#endif
