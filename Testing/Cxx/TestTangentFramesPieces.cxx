// SPDX-License-Identifier: BSD-3-Clause
// A mesh split into pieces, as a parallel pipeline (ParaView's pvserver, pvbatch under MPI)
// delivers it: the filter asks for one more level of ghost cells, and with them every corner of
// a piece's own cells gets the frame it gets in the whole mesh.
#include "NormalMappingMessages.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace
{
using Pipeline = vtkStreamingDemandDrivenPipeline;

/**
 * Piece p of n of a mesh: its cells [p C / n, (p + 1) C / n), up to MaxGhostLevels of the ghost
 * levels asked for (level k: the cells sharing a point with level k - 1), marked as duplicate
 * cells, and the points they use. "CellId" holds each cell's id in the mesh.
 */
class PieceSource : public vtkPolyDataAlgorithm
{
public:
  static PieceSource* New();
  vtkTypeMacro(PieceSource, vtkPolyDataAlgorithm);

  vtkSmartPointer<vtkPolyData> Mesh;
  int MaxGhostLevels = 1;
  int AskedGhostLevels = -1;

protected:
  PieceSource() { this->SetNumberOfInputPorts(0); }

  int RequestInformation(vtkInformation*,
    vtkInformationVector**,
    vtkInformationVector* out) override
  {
    out->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
    return 1;
  }

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    const vtkIdType piece = info->Get(Pipeline::UPDATE_PIECE_NUMBER());
    const vtkIdType pieces = info->Get(Pipeline::UPDATE_NUMBER_OF_PIECES());
    this->AskedGhostLevels = info->Get(Pipeline::UPDATE_NUMBER_OF_GHOST_LEVELS());
    const vtkIdType numCells = this->Mesh->GetNumberOfCells();
    std::vector<int> level(static_cast<size_t>(numCells), -1);
    std::fill(level.begin() + piece * numCells / pieces,
      level.begin() + (piece + 1) * numCells / pieces,
      0);
    this->Mesh->BuildLinks();
    vtkNew<vtkIdList> points, cells;
    const int levels = std::min(this->AskedGhostLevels, this->MaxGhostLevels);
    for (int l = 1; l <= levels; ++l)
    {
      for (vtkIdType c = 0; c < numCells; ++c)
      {
        if (level[c] != l - 1)
        {
          continue;
        }
        this->Mesh->GetCellPoints(c, points);
        for (vtkIdType k = 0; k < points->GetNumberOfIds(); ++k)
        {
          this->Mesh->GetPointCells(points->GetId(k), cells);
          for (vtkIdType j = 0; j < cells->GetNumberOfIds(); ++j)
          {
            int& other = level[cells->GetId(j)];
            other = other < 0 ? l : other;
          }
        }
      }
    }
    // The points of the kept cells, in the mesh's order, and the cells re-pointed to them.
    const vtkIdType numPoints = this->Mesh->GetNumberOfPoints();
    std::vector<vtkIdType> newId(static_cast<size_t>(numPoints), -1);
    for (vtkIdType c = 0; c < numCells; ++c)
    {
      this->Mesh->GetCellPoints(c, points);
      for (vtkIdType k = 0; level[c] >= 0 && k < points->GetNumberOfIds(); ++k)
      {
        newId[points->GetId(k)] = 0;
      }
    }
    vtkPolyData* output = vtkPolyData::GetData(out);
    vtkNew<vtkPoints> kept;
    vtkPointData* inPD = this->Mesh->GetPointData();
    output->GetPointData()->CopyAllocate(inPD);
    for (vtkIdType p = 0; p < numPoints; ++p)
    {
      if (newId[p] == 0)
      {
        newId[p] = kept->InsertNextPoint(this->Mesh->GetPoint(p));
        output->GetPointData()->CopyData(inPD, p, newId[p]);
      }
    }
    vtkNew<vtkCellArray> polys;
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("CellId");
    vtkNew<vtkUnsignedCharArray> ghosts;
    ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
    for (vtkIdType c = 0; c < numCells; ++c)
    {
      if (level[c] >= 0)
      {
        this->Mesh->GetCellPoints(c, points);
        polys->InsertNextCell(static_cast<int>(points->GetNumberOfIds()));
        for (vtkIdType k = 0; k < points->GetNumberOfIds(); ++k)
        {
          polys->InsertCellPoint(newId[points->GetId(k)]);
        }
        ids->InsertNextValue(c);
        ghosts->InsertNextValue(level[c] > 0 ? vtkDataSetAttributes::DUPLICATECELL : 0);
      }
    }
    output->SetPoints(kept);
    output->SetPolys(polys);
    output->GetCellData()->AddArray(ids);
    output->GetCellData()->AddArray(ghosts);
    return 1;
  }
};
vtkStandardNewMacro(PieceSource);

/// The frame (tangent, sign) at output point p.
struct Frame
{
  double Tangent[3];
  double Sign;
};
Frame FrameAt(vtkPolyData* output, vtkIdType p)
{
  Frame f;
  output->GetPointData()->GetArray("Tangents")->GetTuple(p, f.Tangent);
  f.Sign = output->GetPointData()->GetArray("TangentSigns")->GetComponent(p, 0);
  return f;
}

/// The largest angle (degrees) between the frames of the own cells' corners of one piece's
/// output and of the same corners in the whole mesh's output; 180 where the signs differ.
double LargestAngleToWhole(vtkPolyData* piece, vtkPolyData* whole)
{
  vtkDataArray* ids = piece->GetCellData()->GetArray("CellId");
  vtkDataArray* ghosts = piece->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  vtkNew<vtkIdList> own, reference;
  double largest = 0.0;
  for (vtkIdType c = 0; c < piece->GetNumberOfCells(); ++c)
  {
    if (ghosts->GetComponent(c, 0) != 0)
    {
      continue;
    }
    piece->GetCellPoints(c, own);
    whole->GetCellPoints(static_cast<vtkIdType>(ids->GetComponent(c, 0)), reference);
    for (vtkIdType k = 0; k < own->GetNumberOfIds(); ++k)
    {
      const Frame a = FrameAt(piece, own->GetId(k));
      const Frame b = FrameAt(whole, reference->GetId(k));
      largest = std::max(largest,
        a.Sign != b.Sign
          ? 180.0
          : vtkMath::DegreesFromRadians(vtkMath::AngleBetweenVectors(a.Tangent, b.Tangent)));
    }
  }
  return largest;
}
} // namespace

TEST(TangentFramesPieces, PiecesWithOneGhostLevelGetTheWholeMeshFrames)
{
  // A mirrored torus: mirror seams (split points) and ordinary seams cross the pieces.
  vtkNormalMapping::TorusOptions options;
  options.U = 48;
  options.V = 16;
  options.MirrorU = true;
  const auto mesh = vtkNormalMapping::MakeTorus(options);
  const int pieces = 3;
  for (const int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> whole;
    whole->SetMethod(method);
    whole->SetInputData(mesh);
    whole->Update();
    // With the ghost level the filter asks for, and with none (a source that cannot make ghost
    // cells): the latter must differ at the pieces' boundaries, or this comparison proves
    // nothing.
    for (const int provided : { 1, 0 })
    {
      vtkNew<PieceSource> source;
      source->Mesh = mesh;
      source->MaxGhostLevels = provided;
      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetMethod(method);
      filter->SetInputConnection(source->GetOutputPort());
      double largest = 0.0;
      for (int piece = 0; piece < pieces; ++piece)
      {
        Messages messages(filter);
        filter->UpdatePiece(piece, pieces, 0);
        EXPECT_EQ(source->AskedGhostLevels, 1) << "piece " << piece;
        // No message: the filter cannot tell a piece without ghost cells from a whole mesh.
        EXPECT_TRUE(messages.Errors.empty() && messages.Warnings.empty()) << messages.WarningText();
        // The ghost cells stay in the output, marked as ghosts.
        vtkDataArray* ghosts =
          filter->GetOutput()->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName());
        ASSERT_NE(ghosts, nullptr);
        EXPECT_EQ(ghosts->GetRange()[1] > 0, provided > 0);
        largest = std::max(largest, LargestAngleToWhole(filter->GetOutput(), whole->GetOutput()));
      }
      std::cout << vtkPolyDataTangentFrames::GetMethodName(method) << ", " << provided
                << " ghost level(s): largest angle to the whole mesh's frames " << largest
                << " degrees" << std::endl;
      if (provided == 1)
      {
        // The same corners from the same triangles, added in the same order: only rounding may
        // differ (MikkTSpace's positions are placed relative to the piece's bounds). Rounding
        // of float input moves a frame by about 1e-5 degrees; 1e-3 is far below any frame
        // built from other triangles (3.75 degrees here).
        EXPECT_LT(largest, 1e-3);
      }
      else
      {
        EXPECT_GT(largest, 1.0);
      }
    }
  }
}

TEST(TangentFramesPieces, OnePieceAsksForNoGhostLevels)
{
  vtkNormalMapping::TorusOptions options;
  options.U = 8;
  options.V = 4;
  vtkNew<PieceSource> source;
  source->Mesh = vtkNormalMapping::MakeTorus(options);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputConnection(source->GetOutputPort());
  Messages messages(filter);
  filter->Update();
  EXPECT_EQ(source->AskedGhostLevels, 0);
  EXPECT_TRUE(messages.Warnings.empty()) << messages.WarningText();
}
