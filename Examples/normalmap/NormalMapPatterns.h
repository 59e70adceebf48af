// SPDX-License-Identifier: BSD-3-Clause
// Procedural tangent-space normal maps for the normalmap tool (its built-in map and the demo):
// a height field on the unit square, tiled without seams, turned into normals by central
// differences and stored as an 8-bit texture image (row 0 at v = 0, as vtkPNGReader gives).
#ifndef NormalMapPatterns_h
#define NormalMapPatterns_h

#include <vtkSmartPointer.h>

class vtkImageData;

namespace NormalMapPatterns
{
/// How the image stores the tangent-space normal n (x along +u, y along +v, z out).
enum class Encoding
{
  OpenGL,    // RGB = n * 0.5 + 0.5
  DirectX,   // the same with green inverted (y along -v)
  TwoChannel // two components: R, G as OpenGL; the mapper rebuilds z
};

/**
 * Bricks in running bond: `Rows` rows of `Columns` bricks on the unit square, odd rows offset
 * by half a brick; each brick's height rises from the mortar line over `Bevel` (in texture
 * units) to a flat top, with a round rivet of radius `RivetRadius` (texture units; 0: none)
 * and height `RivetHeight` at its centre. `Depth` is the bevel's height in texture units: the
 * bevel slope is Depth / Bevel.
 */
struct Bricks
{
  int Rows = 6;
  int Columns = 4;
  double Bevel = 0.02;
  double Depth = 0.012;
  double RivetRadius = 0.035;
  double RivetHeight = 0.02;
};

/// Height of the pattern at (u, v); periodic with period 1 in u and v.
double BrickHeight(const Bricks& bricks, double u, double v);

/// A size x size normal map of the pattern (texel centres at (i + 0.5) / size).
vtkSmartPointer<vtkImageData> MakeBrickNormalMap(const Bricks& bricks, int size, Encoding encoding);
}

#endif
