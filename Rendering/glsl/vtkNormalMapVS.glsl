// SPDX-License-Identifier: BSD-3-Clause
// Vertex-shader pieces of vtkNormalMapPolyDataMapper. Each block between "//NM::Begin <name>"
// and "//NM::End" is inserted at one of VTK's shader tags when the scene needs it.

//NM::Begin TangentDec
// Model-coordinate tangent; w carries the handedness sign, 0 for tangents without one.
in vec4 nmTangentMC;
out vec4 nmTangentMCVSOutput;
//NM::End

//NM::Begin TangentImpl
  nmTangentMCVSOutput = nmTangentMC;
//NM::End

//NM::Begin TangentUnsignedImpl
  // A 3-component array reads w = 1 (OpenGL's default for a missing component): no sign.
  nmTangentMCVSOutput = vec4(nmTangentMC.xyz, 0.0);
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

//NM::Begin TCoordDec
// The dataset's texture coordinates, for the normal texture while VTK's own tcoord attribute
// holds the color map's coordinates (scalars interpolated before mapping).
in vec2 nmTCoord;
out vec2 nmTCoordVCVSOutput;
//NM::End

//NM::Begin TCoordImpl
  nmTCoordVCVSOutput = nmTCoord;
//NM::End

//NM::Begin TCoordTransformedImpl
  // The actor's texture transform, applied as VTK applies it to its own texture coordinates
  // (VTK declares tcMatrix when the actor has one and VTK has texture coordinates of its own,
  // which it has here: the color map's, or the dataset's themselves).
  {
    vec4 nmTCoordH = tcMatrix * vec4(nmTCoord, 0.0, 1.0);
    nmTCoordVCVSOutput = nmTCoordH.xy / nmTCoordH.w;
  }
//NM::End
