// SPDX-License-Identifier: BSD-3-Clause
// Image test: a two-channel (RG, z reconstructed) DirectX map of rivets on a quad and a sphere,
// each dome lit from the upper left like the light. It fails when the map's green is read in the
// other convention or the map is dropped (NormalMapImageTest.h).
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"

int TestNormalMapTwoChannelDirectXMap(int argc, char* argv[])
{
  using Mapper = vtkNormalMapPolyDataMapper;
  return nmtest::RunEncodingTest(argc,
    argv,
    nmtest::Storage::TwoChannelDirectX,
    Mapper::TWO_CHANNEL_DIRECTX,
    Mapper::TWO_CHANNEL_OPENGL);
}
