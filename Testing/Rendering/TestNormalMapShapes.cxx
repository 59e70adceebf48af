// SPDX-License-Identifier: BSD-3-Clause
// Plane (bricks), sphere (rivets) and torus (sine bump), each with tangents from
// vtkPolyDataTangentFrames, in Phong (top row) and PBR (bottom row). It fails when every map's
// green is read in the other convention, or the maps are dropped.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkProperty.h"

int TestNormalMapShapes(int argc, char* argv[])
{
  vtkNormalMapping::TorusOptions torusOptions;
  torusOptions.U = 96;
  torusOptions.V = 48;
  vtkSmartPointer<vtkPolyData> meshes[3] = { nmtest::WithTangents(nmtest::MakeQuad(8)),
    nmtest::WithTangents(nmtest::MakeSphere(48)),
    nmtest::WithTangents(vtkNormalMapping::MakeTorus(torusOptions)) };
  const nmtest::Pattern patterns[3] = {
    nmtest::Pattern::Bricks, nmtest::Pattern::Rivets, nmtest::Pattern::SineBump
  };
  vtkSmartPointer<vtkTexture> textures[3];
  for (int i = 0; i < 3; ++i)
  {
    textures[i] = nmtest::MakeNormalTexture(
      nmtest::MakeNormalMapImage(patterns[i], 256, nmtest::Storage::OpenGL));
  }
  const double rotateX[3] = { 0.0, -60.0, -50.0 };

  return nmtest::RunImageTest(argc,
    argv,
    { "the other green convention", "the maps dropped" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(600, 400);
      for (int row = 0; row < 2; ++row)
      {
        for (int column = 0; column < 3; ++column)
        {
          nmtest::Panel p;
          p.Mesh = meshes[column];
          p.Texture = alteration == 1 ? nullptr : textures[column].Get();
          p.Encoding = alteration == 0 ? vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX
                                       : vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
          p.Interpolation = row == 0 ? VTK_PHONG : VTK_PBR;
          p.RotateX = rotateX[column];
          p.Zoom = 1.3;
          nmtest::AddPanel(window, 3, 2, column, row, p);
        }
      }
      return window;
    });
}
