// SPDX-License-Identifier: BSD-3-Clause
// Vertex-shader pieces of vtkNormalMapPolyDataMapper. Each block between "//NM::Begin <name>"
// and "//NM::End" is inserted at one of VTK's shader tags when the scene needs it.

//NM::Begin TangentDec
// Model-coordinate tangent; w carries the handedness sign. A 3-component tangent array reads
// w = 1 (OpenGL's default for a missing component), the sign of unsigned tangents.
in vec4 nmTangentMC;
out vec4 nmTangentMCVSOutput;
//NM::End

//NM::Begin TangentImpl
  nmTangentMCVSOutput = nmTangentMC;
//NM::End

//NM::Begin TangentSignDec
// The sign as its own attribute (vtkPolyDataTangentFrames' TangentSigns array).
in vec3 nmTangentMC;
in float nmTangentSignMC;
out vec4 nmTangentMCVSOutput;
//NM::End

//NM::Begin TangentSignImpl
  nmTangentMCVSOutput = vec4(nmTangentMC, nmTangentSignMC);
//NM::End
