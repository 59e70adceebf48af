// SPDX-License-Identifier: BSD-3-Clause
// Geometry-shader pieces of vtkNormalMapPolyDataMapper, used when VTK draws through a
// geometry shader (for example surfaces with edges): the tangent and the texture coordinates
// pass through unchanged.

//NM::Begin TangentDec
in vec4 nmTangentMCVSOutput[];
out vec4 nmTangentMCGSOutput;
//NM::End

//NM::Begin TangentImpl
nmTangentMCGSOutput = nmTangentMCVSOutput[i];
//NM::End

//NM::Begin TCoordDec
in vec2 nmTCoordVCVSOutput[];
out vec2 nmTCoordVCGSOutput;
//NM::End

//NM::Begin TCoordImpl
nmTCoordVCGSOutput = nmTCoordVCVSOutput[i];
//NM::End
