// SPDX-License-Identifier: BSD-3-Clause
// A mesh held in the MikkTSpace kernel's input layout, for its tests and benchmark.
#ifndef MikkTSpaceKernelMesh_h
#define MikkTSpaceKernelMesh_h

#include "vtkMikkTSpaceKernel.h"

#include <array>
#include <initializer_list>
#include <vector>

namespace NormalMappingTesting
{
struct KernelMesh
{
  std::vector<long long> Offsets{ 0 };
  std::vector<long long> Conn;
  std::vector<float> P, N, U;

  long long AddPoint(std::array<float, 3> p, std::array<float, 3> n, std::array<float, 2> uv)
  {
    P.insert(P.end(), p.begin(), p.end());
    N.insert(N.end(), n.begin(), n.end());
    U.insert(U.end(), uv.begin(), uv.end());
    return static_cast<long long>(P.size() / 3 - 1);
  }
  void AddFace(std::initializer_list<long long> ids)
  {
    Conn.insert(Conn.end(), ids.begin(), ids.end());
    Offsets.push_back(static_cast<long long>(Conn.size()));
  }
  vtkNormalMapping::mikk::MeshInput Input() const
  {
    vtkNormalMapping::mikk::MeshInput in;
    in.NumberOfFaces = static_cast<long long>(Offsets.size()) - 1;
    in.FaceOffsets = Offsets.data();
    in.FaceConnectivity = Conn.data();
    in.NumberOfPoints = static_cast<long long>(P.size() / 3);
    in.Positions = P.data();
    in.Normals = N.data();
    in.TCoords = U.data();
    return in;
  }
};
}

#endif
