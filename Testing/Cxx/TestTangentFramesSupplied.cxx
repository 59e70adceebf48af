// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames with supplied tangents (SuppliedTangents KEEP / KEEP_VALID) and the
// checks behind it (vtkTangentFrameChecks.h), on hand-made meshes with one defect each.
#include "NormalMappingGrid.h"

#include "vtkPolyDataTangentFrames.h"
#include "vtkTangentFrameChecks.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

namespace
{
constexpr double Pi = 3.14159265358979323846;

/**
 * A flat grid in the xy plane, normal +z. With `mirror`, u = 2 min(s, 1 - s): the half s > 1/2
 * is a mirrored UV island (tangent -x, sign -1) and the column s = 1/2 a mirror seam whose
 * points are shared by both halves; without it u = s (tangent +x, sign +1 everywhere).
 */
vtkSmartPointer<vtkPolyData> Plane(bool mirror, int n = 8)
{
  return NormalMappingTesting::MakeGrid(
    n,
    n,
    [](double s, double t) {
      return std::array<double, 3>{ s, t, 0.0 };
    },
    [](double, double) {
      return std::array<double, 3>{ 0.0, 0.0, 1.0 };
    },
    [mirror](double s, double t) {
      return std::array<double, 2>{ mirror ? 2.0 * std::min(s, 1.0 - s) : s, t };
    });
}

/// The x coordinate of point p (the grid's s).
double S(vtkPolyData* mesh, vtkIdType p)
{
  return mesh->GetPoint(p)[0];
}

/**
 * Supplied frames, as glTF's TANGENT (4 components, w the sign) named "TANGENT": the true
 * frame of Plane(mirror) (tangent +-x, sign +-1) turned by `turn` radians about the normal. A
 * turned tangent is still unit, perpendicular and of the right sign (a valid frame the filter would
 * not compute).
 */
vtkSmartPointer<vtkFloatArray> SuppliedVec4(vtkPolyData* mesh, double turn, bool mirror)
{
  auto t = vtkSmartPointer<vtkFloatArray>::New();
  t->SetName("TANGENT");
  t->SetNumberOfComponents(4);
  t->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double sign = mirror && S(mesh, p) > 0.5 + 1e-9 ? -1.0 : 1.0;
    const double angle = turn + (sign < 0.0 ? Pi : 0.0);
    t->SetTuple4(p, std::cos(angle), std::sin(angle), 0.0, sign);
  }
  mesh->GetPointData()->AddArray(t);
  return t;
}

struct SuppliedRun
{
  vtkNew<vtkPolyDataTangentFrames> Filter;
  vtkNew<vtkTest::ErrorObserver> Messages;
  vtkPolyData* Output = nullptr;

  SuppliedRun(vtkPolyData* input, int supplied, const char* name = "TANGENT")
  {
    this->Filter->SetInputData(input);
    this->Filter->SetSuppliedTangents(supplied);
    this->Filter->SetSuppliedTangentsArrayName(name);
    this->Filter->AddObserver(vtkCommand::WarningEvent, this->Messages);
    this->Filter->AddObserver(vtkCommand::ErrorEvent, this->Messages);
  }
  vtkPolyData* Update()
  {
    this->Filter->Update();
    this->Output = this->Filter->GetOutput();
    return this->Output;
  }
  std::array<double, 4> Frame(vtkIdType p) const
  {
    double t[3];
    this->Output->GetPointData()->GetArray("Tangents")->GetTuple(p, t);
    return {
      t[0], t[1], t[2], this->Output->GetPointData()->GetArray("TangentSigns")->GetComponent(p, 0)
    };
  }
};

/// Whether output point p of `run` has the frame `expected` (the float storage rounds by 2^-24;
/// 1e-6 is well above that and far below any defect the tests plant).
::testing::AssertionResult HasFrame(const SuppliedRun& run,
  vtkIdType p,
  const std::array<double, 4>& expected)
{
  const std::array<double, 4> f = run.Frame(p);
  for (int c = 0; c < 4; ++c)
  {
    if (!(std::abs(f[c] - expected[c]) <= 1e-6))
    {
      return ::testing::AssertionFailure()
        << "point " << p << ": (" << f[0] << ", " << f[1] << ", " << f[2] << ", " << f[3]
        << ") instead of (" << expected[0] << ", " << expected[1] << ", " << expected[2] << ", "
        << expected[3] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

std::array<double, 4> Supplied(vtkDataArray* t, vtkIdType p)
{
  return {
    t->GetComponent(p, 0), t->GetComponent(p, 1), t->GetComponent(p, 2), t->GetComponent(p, 3)
  };
}

constexpr double Turn = 20.0 * Pi / 180.0;
}

TEST(TangentFramesSupplied, DefaultRecomputesAndKeepValidKeepsGoodFrames)
{
  auto mesh = Plane(false);
  auto supplied = SuppliedVec4(mesh, Turn, false);
  SuppliedRun recompute(mesh, vtkPolyDataTangentFrames::RECOMPUTE);
  EXPECT_EQ(
    vtkPolyDataTangentFrames::RECOMPUTE, vtkNew<vtkPolyDataTangentFrames>()->GetSuppliedTangents());
  recompute.Update();
  SuppliedRun keepValid(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
  keepValid.Update();
  EXPECT_EQ(0, keepValid.Filter->GetNumberOfReplacedTangents());
  EXPECT_FALSE(keepValid.Messages->GetWarning()) << keepValid.Messages->GetWarningMessage();
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    EXPECT_TRUE(HasFrame(recompute, p, { 1.0, 0.0, 0.0, 1.0 }));
    EXPECT_TRUE(HasFrame(keepValid, p, Supplied(supplied, p)));
  }
}

TEST(TangentFramesSupplied, EachDefectIsCountedAndReplaced)
{
  // One point per defect, inside the plane (all its triangles have the +1 winding).
  struct Case
  {
    const char* Name;
    std::array<double, 4> Frame;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double c = std::cos(Pi / 4);
  const Case cases[] = {
    { "flipped w", { 1.0, 0.0, 0.0, -1.0 } },
    { "not perpendicular", { c, 0.0, c, 1.0 } },
    { "not unit", { 1.5, 0.0, 0.0, 1.0 } },
    { "NaN", { nan, 0.0, 0.0, 1.0 } },
    { "w not +-1", { 1.0, 0.0, 0.0, 0.0 } },
  };
  for (int k = 0; k < 5; ++k)
  {
    SCOPED_TRACE(cases[k].Name);
    auto mesh = Plane(false);
    auto supplied = SuppliedVec4(mesh, 0.0, false);
    const vtkIdType bad = 4 * 9 + 4; // the grid's centre point (9 points per column)
    supplied->SetTuple(bad, cases[k].Frame.data());
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
    run.Update();
    vtkPolyDataTangentFrames* f = run.Filter;
    EXPECT_EQ(1, f->GetNumberOfReplacedTangents());
    EXPECT_EQ(k == 0 || k == 4 ? 1 : 0, f->GetNumberOfWrongSignTangents());
    EXPECT_EQ(k == 1 ? 1 : 0, f->GetNumberOfNonPerpendicularTangents());
    EXPECT_EQ(k == 2 ? 1 : 0, f->GetNumberOfNonUnitTangents());
    EXPECT_EQ(k == 3 ? 1 : 0, f->GetNumberOfNonFiniteTangents());
    // The replaced point has the computed frame, the others their own.
    EXPECT_TRUE(HasFrame(run, bad, { 1.0, 0.0, 0.0, 1.0 }));
    EXPECT_TRUE(HasFrame(run, bad + 1, Supplied(supplied, bad + 1)));
  }
}

TEST(TangentFramesSupplied, DefectsAreJudgedAtTheDocumentedTolerances)
{
  // The documented tolerances (vtkTangentFrameChecks.h, docs/filter.md), written out so that
  // a change of the defaults fails here: 1e-2 for | |T| - 1 | and | |w| - 1 |, 2e-2 for
  // |T.N| / |T|. Each with a frame 1.5 times beyond it (replaced) and one half within it (kept
  // as supplied, its w written as its sign).
  const double unitTolerance = 1e-2, perpendicularTolerance = 2e-2, signTolerance = 1e-2;
  const double tilt = 1.5 * perpendicularTolerance, inTilt = 0.5 * perpendicularTolerance;
  struct Case
  {
    const char* Name;
    std::array<double, 4> Frame;
    bool Replaced;
  };
  const Case cases[] = {
    { "long", { 1.0 + 1.5 * unitTolerance, 0.0, 0.0, 1.0 }, true },
    { "slightly long", { 1.0 + 0.5 * unitTolerance, 0.0, 0.0, 1.0 }, false },
    { "tilted", { std::sqrt(1.0 - tilt * tilt), 0.0, tilt, 1.0 }, true },
    { "slightly tilted", { std::sqrt(1.0 - inTilt * inTilt), 0.0, inTilt, 1.0 }, false },
    { "w off", { 1.0, 0.0, 0.0, 1.0 + 1.5 * signTolerance }, true },
    { "w slightly off", { 1.0, 0.0, 0.0, 1.0 + 0.5 * signTolerance }, false },
  };
  for (const Case& k : cases)
  {
    SCOPED_TRACE(k.Name);
    auto mesh = Plane(false);
    auto supplied = SuppliedVec4(mesh, 0.0, false);
    const vtkIdType bad = 4 * 9 + 4; // the grid's centre point (9 points per column)
    supplied->SetTuple(bad, k.Frame.data());
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
    run.Update();
    EXPECT_EQ(k.Replaced ? 1 : 0, run.Filter->GetNumberOfReplacedTangents());
    const std::array<double, 4> kept = { k.Frame[0], k.Frame[1], k.Frame[2], 1.0 };
    EXPECT_TRUE(
      HasFrame(run, bad, k.Replaced ? std::array<double, 4>{ 1.0, 0.0, 0.0, 1.0 } : kept));
  }
}

TEST(TangentFramesSupplied, SignsOfVDownCoordinatesWithoutTheFlipAreAllReplaced)
{
  // Signs computed on v-down coordinates without negating them: every w is the opposite of
  // what the winding asks (the MosquitoInAmber defect).
  auto mesh = Plane(true);
  auto supplied = SuppliedVec4(mesh, 0.0, true);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    supplied->SetComponent(p, 3, -supplied->GetComponent(p, 3));
  }
  std::string found;
  const auto arrays = vtkNormalMapping::FindSuppliedFrames(mesh, "TANGENT", found);
  ASSERT_TRUE(arrays.IsUsable()) << found;
  const auto check = vtkNormalMapping::CheckSuppliedFrames(
    mesh, mesh->GetPointData()->GetNormals(), mesh->GetPointData()->GetTCoords(), arrays, false);
  const vtkIdType seam = 9; // the column s = 1/2 has both windings
  EXPECT_EQ(mesh->GetNumberOfPoints() - seam, check.Counts.SignAgainstWinding);
  EXPECT_EQ(seam, check.Counts.MixedWinding);
  EXPECT_EQ(0, check.Counts.SignAgreesWithWinding);
  // The same signs are right for glTF's v-down convention: only the seam is wrong then.
  const auto vDown = vtkNormalMapping::CheckSuppliedFrames(
    mesh, mesh->GetPointData()->GetNormals(), mesh->GetPointData()->GetTCoords(), arrays, true);
  EXPECT_EQ(0, vDown.Counts.SignAgainstWinding);
  EXPECT_EQ(seam, vDown.Counts.Failed);
}

TEST(TangentFramesSupplied, SharedMirrorSeamPointsAreReplacedAndSplit)
{
  auto mesh = Plane(true);
  auto supplied = SuppliedVec4(mesh, Turn, true);
  const vtkIdType seam = 9;
  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
    for (bool splitting : { true, false })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (splitting ? ", splitting" : ", no splitting"));
      SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
      run.Filter->SetMethod(method);
      run.Filter->SetSplitting(splitting);
      run.Update();
      EXPECT_EQ(seam, run.Filter->GetNumberOfReplacedTangents());
      EXPECT_EQ(seam, run.Filter->GetNumberOfWrongSignTangents());
      EXPECT_EQ(splitting ? seam : 0, run.Filter->GetNumberOfSplitPoints());
      ASSERT_EQ(
        mesh->GetNumberOfPoints() + (splitting ? seam : 0), run.Output->GetNumberOfPoints());
      for (vtkIdType p = 0; p < run.Output->GetNumberOfPoints(); ++p)
      {
        const bool onSeam = p >= mesh->GetNumberOfPoints() || std::abs(S(mesh, p) - 0.5) < 1e-9;
        if (!onSeam)
        {
          EXPECT_TRUE(HasFrame(run, p, Supplied(supplied, p)));
        }
        else if (splitting && method != vtkPolyDataTangentFrames::MIKKTSPACE)
        {
          // The seam point takes the +1 side, its copy (appended) the -1 side.
          const double sign = p >= mesh->GetNumberOfPoints() ? -1.0 : 1.0;
          EXPECT_TRUE(HasFrame(run, p, { sign, 0.0, 0.0, sign }));
        }
      }
    }
}

TEST(TangentFramesSupplied, KeepUsesFramesAsTheyAreAndReplacesOnlyNonFinite)
{
  auto mesh = Plane(false);
  auto supplied = SuppliedVec4(mesh, 0.0, false);
  const double c = std::cos(Pi / 4);
  supplied->SetTuple4(10, c, 0.0, c, 1.0); // not perpendicular: kept as it is
  supplied->SetTuple4(11, std::numeric_limits<double>::infinity(), 0.0, 0.0, 1.0);
  supplied->SetTuple4(12, 1.0, 0.0, 0.0, -1.0); // against the winding: KEEP does not look
  SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP);
  run.Filter->ComputeBitangentsOn();
  run.Update();
  EXPECT_EQ(1, run.Filter->GetNumberOfReplacedTangents());
  EXPECT_EQ(1, run.Filter->GetNumberOfNonPerpendicularTangents());
  EXPECT_EQ(1, run.Filter->GetNumberOfNonFiniteTangents());
  EXPECT_NE(std::string::npos, run.Messages->GetWarningMessage().find("NaN or infinite"));
  EXPECT_TRUE(HasFrame(run, 10, { c, 0.0, c, 1.0 }));
  EXPECT_TRUE(HasFrame(run, 11, { 1.0, 0.0, 0.0, 1.0 }));
  // Bitangent = sign * cross(N, T) of the kept frame: (0, c, 0) for T = (c, 0, c), N = z.
  double b[3];
  run.Output->GetPointData()->GetArray("Bitangents")->GetTuple(10, b);
  EXPECT_NEAR(c, b[1], 1e-6);
  EXPECT_NEAR(0.0, b[0], 1e-6);
  // The kept sign -1 turns the bitangent: -cross(z, x) = (0, -1, 0).
  EXPECT_TRUE(HasFrame(run, 12, { 1.0, 0.0, 0.0, -1.0 }));
  run.Output->GetPointData()->GetArray("Bitangents")->GetTuple(12, b);
  EXPECT_NEAR(-1.0, b[1], 1e-6);
  EXPECT_EQ(vtkPolyDataTangentFrames::TangentsArrayName(),
    std::string(run.Output->GetPointData()->GetTangents()->GetName()));
}

TEST(TangentFramesSupplied, InvalidNormalsAreCountedWhetherFramesAreKeptOrComputed)
{
  // One zero and one NaN normal: every mode counts both, also KEEP and KEEP_VALID when they keep
  // every frame and compute none (the NaN normal's frame fails KEEP_VALID's check and is computed;
  // KEEP keeps both as they are).
  auto mesh = Plane(false);
  SuppliedVec4(mesh, 0.0, false);
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  normals->SetTuple3(20, 0.0, 0.0, 0.0);
  normals->SetTuple3(21, std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0);
  for (int mode : { vtkPolyDataTangentFrames::RECOMPUTE,
         vtkPolyDataTangentFrames::KEEP,
         vtkPolyDataTangentFrames::KEEP_VALID })
  {
    for (bool cellTangents : { false, true })
    {
      SCOPED_TRACE("mode " + std::to_string(mode) + (cellTangents ? ", cell tangents" : ""));
      SuppliedRun run(mesh, mode);
      run.Filter->SetComputeCellTangents(cellTangents);
      run.Update();
      EXPECT_EQ(2, run.Filter->GetNumberOfInvalidNormals());
    }
  }
}

TEST(TangentFramesSupplied, KeepReplacesTangentsTooLongForTheOutputPrecision)
{
  // Double tangents that float output cannot hold would be written as infinity: one longer than
  // FLT_MAX, and one whose bitangent (as long, rounded) could overflow. KEEP computes their
  // frames, as for NaN; a long tangent float holds (1e30) is kept as it is. Double output holds
  // all three.
  auto mesh = Plane(false);
  vtkNew<vtkDoubleArray> t;
  t->SetName("TANGENT");
  t->SetNumberOfComponents(4);
  t->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    t->SetTuple4(p, 1.0, 0.0, 0.0, 1.0);
  }
  t->SetTuple4(10, 1e300, 0.0, 0.0, 1.0);
  t->SetTuple4(11, 0.9 * FLT_MAX, 0.0, 0.0, 1.0);
  t->SetTuple4(12, 1e30, 0.0, 0.0, 1.0);
  mesh->GetPointData()->AddArray(t);
  for (const int precision : { vtkAlgorithm::SINGLE_PRECISION, vtkAlgorithm::DOUBLE_PRECISION })
  {
    const bool single = precision == vtkAlgorithm::SINGLE_PRECISION;
    SCOPED_TRACE(single ? "float output" : "double output");
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP);
    run.Filter->SetOutputPrecision(precision);
    run.Filter->ComputeBitangentsOn();
    run.Update();
    EXPECT_EQ(single ? 2 : 0, run.Filter->GetNumberOfReplacedTangents());
    EXPECT_EQ(single ? 2 : 0, run.Filter->GetNumberOfNonFiniteTangents());
    EXPECT_EQ(single,
      run.Messages->GetWarningMessage().find("too large for the output's precision") !=
        std::string::npos)
      << run.Messages->GetWarningMessage();
    vtkPointData* pd = run.Output->GetPointData();
    for (const char* name : { "Tangents", "Bitangents" })
    {
      vtkDataArray* a = pd->GetArray(name);
      ASSERT_NE(a, nullptr) << name;
      for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
      {
        ASSERT_TRUE(std::isfinite(a->GetComponent(i / 3, static_cast<int>(i % 3))))
          << name << " value " << i;
      }
    }
    if (single)
    {
      EXPECT_TRUE(HasFrame(run, 10, { 1.0, 0.0, 0.0, 1.0 }));
      EXPECT_TRUE(HasFrame(run, 11, { 1.0, 0.0, 0.0, 1.0 }));
    }
    else
    {
      EXPECT_EQ(1e300, pd->GetArray("Tangents")->GetComponent(10, 0));
    }
    EXPECT_EQ(
      single ? static_cast<double>(1e30f) : 1e30, pd->GetArray("Tangents")->GetComponent(12, 0));
  }
}

TEST(TangentFramesSupplied, CellTangentsAreComputedWhenEveryFrameIsKept)
{
  // Every supplied frame passes, so no point frame is computed; the cell tangents asked for
  // are still computed, as without supplied tangents.
  auto mesh = Plane(false);
  auto supplied = SuppliedVec4(mesh, Turn, false);
  SuppliedRun keep(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
  keep.Filter->ComputeCellTangentsOn();
  keep.Update();
  EXPECT_EQ(0, keep.Filter->GetNumberOfReplacedTangents());
  SuppliedRun recompute(mesh, vtkPolyDataTangentFrames::RECOMPUTE);
  recompute.Filter->ComputeCellTangentsOn();
  recompute.Update();
  vtkDataArray* kept = keep.Output->GetCellData()->GetTangents();
  vtkDataArray* computed = recompute.Output->GetCellData()->GetTangents();
  ASSERT_NE(kept, nullptr);
  ASSERT_NE(computed, nullptr);
  ASSERT_EQ(kept->GetNumberOfTuples(), mesh->GetNumberOfCells());
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(computed->GetComponent(c, k), kept->GetComponent(c, k)) << "cell " << c;
    }
  }
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    EXPECT_TRUE(HasFrame(keep, p, Supplied(supplied, p)));
  }
}

TEST(TangentFramesSupplied, KeptPointsAreNotCountedAsFallbacks)
{
  // Collapsed texture coordinates give no triangle a frame, so every frame the filter computes
  // is a fallback (the weighted methods count the triangles as degenerate; MIKKTSPACE does not).
  // With KEEP and cell tangents it computes the point frames too, but keeps every supplied one: no
  // point gets a fallback frame, and none is counted as one (MIKKTSPACE counts face corners, and
  // leaves out those of kept points).
  auto mesh = Plane(false);
  auto supplied = SuppliedVec4(mesh, Turn, false);
  mesh->GetPointData()->GetTCoords()->Fill(0.0);
  for (int method : { vtkPolyDataTangentFrames::UNWEIGHTED,
         vtkPolyDataTangentFrames::AREA_WEIGHTED,
         vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
         vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    SuppliedRun recompute(mesh, vtkPolyDataTangentFrames::RECOMPUTE);
    recompute.Filter->SetMethod(method);
    recompute.Update();
    // MIKKTSPACE counts face corners, every one here.
    const bool mikk = method == vtkPolyDataTangentFrames::MIKKTSPACE;
    EXPECT_EQ(mikk ? 3 * 2 * 8 * 8 : mesh->GetNumberOfPoints(),
      recompute.Filter->GetNumberOfFallbackPoints());
    SuppliedRun keep(mesh, vtkPolyDataTangentFrames::KEEP);
    keep.Filter->SetMethod(method);
    keep.Filter->ComputeCellTangentsOn();
    keep.Update();
    EXPECT_EQ(mikk ? 0 : 2 * 8 * 8, keep.Filter->GetNumberOfDegenerateTriangles());
    EXPECT_EQ(0, keep.Filter->GetNumberOfFallbackPoints());
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      EXPECT_TRUE(HasFrame(keep, p, Supplied(supplied, p)));
    }
  }
}

TEST(TangentFramesSupplied, KeptFramesSplitNoPoint)
{
  // KEEP on a mirrored plane whose seam points are shared: every kept point has its one
  // supplied frame, so frames computed for other reasons (the cell tangents, or one NaN tangent
  // away from the seam) split no point and count no conflict: the output's points are the
  // input's, whatever else is asked.
  auto mesh = Plane(true);
  auto supplied = SuppliedVec4(mesh, Turn, true);
  const vtkIdType nan = 1; // on the first row, s = 1/7: not on the seam
  ASSERT_GT(std::abs(S(mesh, nan) - 0.5), 0.1);
  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    for (bool withNaN : { false, true })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (withNaN ? ", a NaN tangent" : ", cell tangents"));
      auto input = vtkSmartPointer<vtkPolyData>::New();
      input->DeepCopy(mesh);
      if (withNaN)
      {
        input->GetPointData()->GetArray("TANGENT")->SetComponent(nan, 0, std::nan(""));
      }
      SuppliedRun run(input, vtkPolyDataTangentFrames::KEEP);
      run.Filter->SetMethod(method);
      run.Filter->SetComputeCellTangents(!withNaN);
      run.Update();
      EXPECT_EQ(withNaN ? 1 : 0, run.Filter->GetNumberOfReplacedTangents());
      EXPECT_EQ(0, run.Filter->GetNumberOfSplitPoints());
      EXPECT_EQ(0, run.Filter->GetNumberOfHandednessConflicts());
      ASSERT_EQ(mesh->GetNumberOfPoints(), run.Output->GetNumberOfPoints());
      for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
      {
        if (!withNaN || p != nan)
        {
          EXPECT_TRUE(HasFrame(run, p, Supplied(supplied, p)));
        }
      }
    }
  }
}

TEST(TangentFramesSupplied, AnInputArrayNamedBitangentsIsNeverWritten)
{
  // Some frames replaced, so that computed frames are written: without ComputeBitangents the
  // input's own Bitangents passes through unchanged, and with it the output gets computed ones.
  // Float unit vectors' squared length is within 1e-6 of 1; 1e-5 allows for that.
  // Without a mirror seam the output shares the input's point arrays; with one it has copies.
  for (const int run : { 0, 1, 2, 3 })
  {
    const bool bitangents = run & 1;
    const bool mirror = run & 2;
    SCOPED_TRACE(std::string(bitangents ? "ComputeBitangents on" : "ComputeBitangents off") +
      (mirror ? ", mirrored" : ""));
    auto mesh = Plane(mirror);
    auto supplied = SuppliedVec4(mesh, Turn, mirror);
    supplied->SetTuple4(0, 5.0, 0.0, 0.0, 1.0); // not unit: replaced
    vtkFloatArray* user = NormalMappingTesting::AddFilledArray(
      mesh->GetPointData(), mesh->GetNumberOfPoints(), "Bitangents", 3, 7.0);
    SuppliedRun filter(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
    filter.Filter->SetComputeBitangents(bitangents);
    filter.Update();
    ASSERT_GT(filter.Filter->GetNumberOfReplacedTangents(), 0);
    for (vtkIdType i = 0; i < user->GetNumberOfValues(); ++i)
    {
      ASSERT_EQ(user->GetValue(i), 7.0f) << "input value " << i;
    }
    // The output's: the input's values (with copies for split points), or computed unit vectors.
    vtkDataArray* out = filter.Output->GetPointData()->GetArray("Bitangents");
    ASSERT_NE(out, nullptr);
    ASSERT_EQ(out->GetNumberOfTuples(), filter.Output->GetNumberOfPoints());
    for (vtkIdType p = 0; p < out->GetNumberOfTuples(); ++p)
    {
      double b[3];
      out->GetTuple(p, b);
      const double expected = bitangents ? 1.0 : 3.0 * 7.0 * 7.0;
      ASSERT_NEAR(b[0] * b[0] + b[1] * b[1] + b[2] * b[2], expected, 1e-5) << "point " << p;
    }
  }
}

TEST(TangentFramesSupplied, CheckCountsSignsAndLargestErrors)
{
  // The counts `normalmap check` reports: the points with a positive sign, and the largest
  // length error and |cos| to the normal over the finite tangents; a point whose normal is zero
  // cannot be checked for perpendicularity and counts as not perpendicular.
  auto mesh = Plane(true);
  auto supplied = SuppliedVec4(mesh, 0.0, true); // right frames: -1 on the mirrored half
  vtkIdType positive = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    positive += supplied->GetComponent(p, 3) > 0.0 ? 1 : 0;
  }
  ASSERT_GT(positive, 0);
  ASSERT_LT(positive, mesh->GetNumberOfPoints());
  const double longer = 1.004, tilt = 0.01; // both within the default tolerances
  supplied->SetTuple4(10, longer, 0.0, 0.0, 1.0);
  supplied->SetTuple4(11, std::sqrt(1.0 - tilt * tilt), 0.0, tilt, 1.0);
  supplied->SetTuple4(12, std::numeric_limits<double>::quiet_NaN(), 0.0, 5.0, 1.0); // not measured
  mesh->GetPointData()->GetNormals()->SetTuple3(13, 0.0, 0.0, 0.0);
  std::string problem;
  const auto arrays = vtkNormalMapping::FindSuppliedFrames(mesh, "TANGENT", problem);
  ASSERT_TRUE(arrays.IsUsable()) << problem;
  const auto check = vtkNormalMapping::CheckSuppliedFrames(
    mesh, mesh->GetPointData()->GetNormals(), nullptr, arrays, false);
  // 10 to 13 are on the +1 half (s < 1/2); 12 is not finite and not counted.
  EXPECT_EQ(positive - 1, check.Counts.PositiveSigns);
  // The supplied array is float: each component is rounded by up to 6e-8.
  EXPECT_NEAR(longer - 1.0, check.Counts.MaxLengthError, 1e-7);
  EXPECT_NEAR(tilt, check.Counts.MaxCosineToNormal, 1e-7);
  EXPECT_EQ(vtkNormalMapping::DefectNotPerpendicular, check.Defects[13]);
  EXPECT_EQ(1, check.Counts.NotPerpendicular);
  EXPECT_EQ(vtkNormalMapping::DefectNonFinite, check.Defects[12]);
  EXPECT_EQ(2, check.Counts.Failed);
}

TEST(TangentFramesSupplied, ThreeComponentsWithSignArray)
{
  auto mesh = Plane(true);
  auto vec4 = SuppliedVec4(mesh, Turn, true);
  vtkNew<vtkDoubleArray> tangents, signs;
  tangents->SetName("Tangents");
  tangents->SetNumberOfComponents(3);
  signs->SetName("TangentSigns");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    tangents->InsertNextTuple3(vec4->GetComponent(p, 0), vec4->GetComponent(p, 1), 0.0);
    signs->InsertNextValue(vec4->GetComponent(p, 3));
  }
  mesh->GetPointData()->RemoveArray("TANGENT");
  mesh->GetPointData()->SetTangents(tangents);
  mesh->GetPointData()->AddArray(signs);
  SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID, "");
  run.Filter->SplittingOff();
  run.Update();
  EXPECT_EQ(9, run.Filter->GetNumberOfReplacedTangents()); // the shared seam column
  EXPECT_TRUE(HasFrame(run, 0, Supplied(vec4, 0)));
  EXPECT_TRUE(
    HasFrame(run, mesh->GetNumberOfPoints() - 1, Supplied(vec4, mesh->GetNumberOfPoints() - 1)));
}

TEST(TangentFramesSupplied, MissingOrUnusableSuppliedArraysWarnAndCompute)
{
  struct Case
  {
    const char* Name;
    const char* ArrayName;
    bool DropNormals;
    const char* Warning;
  };
  const Case cases[] = {
    { "no such array", "Nope", false, "there is no point array 'Nope'" },
    { "3 components, no signs", "Normals", false, "no point array 'TangentSigns'" },
    { "no normals", "TANGENT", true, "no usable point normals" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Name);
    auto mesh = Plane(false);
    SuppliedVec4(mesh, Turn, false);
    if (c.DropNormals)
    {
      mesh->GetPointData()->SetNormals(nullptr);
    }
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID, c.ArrayName);
    run.Update();
    EXPECT_NE(std::string::npos, run.Messages->GetWarningMessage().find(c.Warning))
      << run.Messages->GetWarningMessage();
    EXPECT_TRUE(HasFrame(run, 0, { 1.0, 0.0, 0.0, 1.0 })); // computed, not the supplied one
  }
}

TEST(TangentFramesSupplied, SuppliedArraysOfTheWrongShapeWarnAndCompute)
{
  // Tangents of 2 components, and 3-component tangents whose TangentSigns has 3 components:
  // not readable as frames, so warned about and every frame computed.
  for (const bool signs : { false, true })
  {
    SCOPED_TRACE(signs ? "signs of 3 components" : "tangents of 2 components");
    auto mesh = Plane(false);
    vtkNew<vtkFloatArray> tangents;
    tangents->SetName("TANGENT");
    tangents->SetNumberOfComponents(signs ? 3 : 2);
    tangents->SetNumberOfTuples(mesh->GetNumberOfPoints());
    tangents->Fill(0.0);
    tangents->FillComponent(0, std::cos(Turn));
    tangents->FillComponent(1, std::sin(Turn));
    mesh->GetPointData()->AddArray(tangents);
    if (signs)
    {
      NormalMappingTesting::AddFilledArray(
        mesh->GetPointData(), mesh->GetNumberOfPoints(), "TangentSigns", 3, 1.0);
    }
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
    run.Update();
    const std::string expected = signs
      ? "the supplied sign array 'TangentSigns' has 3 components instead of 1"
      : "the supplied tangent array 'TANGENT' has 2 components instead of 3 or 4";
    EXPECT_NE(std::string::npos, run.Messages->GetWarningMessage().find(expected))
      << run.Messages->GetWarningMessage();
    EXPECT_TRUE(HasFrame(run, 0, { 1.0, 0.0, 0.0, 1.0 })); // computed, not the supplied one
  }
}

TEST(TangentFramesSupplied, ShortOrNonNumericSuppliedTangentsWarnAndCompute)
{
  // A tangent array with fewer tuples than points, and a string array by the requested name:
  // neither holds a frame per point, so warned about and every frame computed.
  for (const bool text : { false, true })
  {
    SCOPED_TRACE(text ? "a string array" : "fewer tuples than points");
    auto mesh = Plane(false);
    if (text)
    {
      vtkNew<vtkStringArray> labels;
      labels->SetName("TANGENT");
      labels->SetNumberOfValues(mesh->GetNumberOfPoints());
      mesh->GetPointData()->AddArray(labels);
    }
    else
    {
      SuppliedVec4(mesh, Turn, false)->SetNumberOfTuples(mesh->GetNumberOfPoints() - 1);
    }
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP);
    run.Update();
    const std::string expected = text
      ? "Cannot use the supplied tangents: the point array 'TANGENT' is not numeric"
      : "Cannot use the supplied tangents: the supplied tangent array 'TANGENT' has " +
        std::to_string(mesh->GetNumberOfPoints() - 1) + " tuples for " +
        std::to_string(mesh->GetNumberOfPoints()) + " points";
    EXPECT_NE(std::string::npos, run.Messages->GetWarningMessage().find(expected))
      << run.Messages->GetWarningMessage();
    EXPECT_TRUE(HasFrame(run, 0, { 1.0, 0.0, 0.0, 1.0 })); // computed, not the supplied one
  }
}

TEST(TangentFramesSupplied, TheActiveTangentsComeBeforeAnArrayNamedTangents)
{
  // Without a name the filter reads the active tangents attribute (3 components, with the
  // point array TangentSigns), and only without one a point array named Tangents.
  auto mesh = Plane(false);
  auto named = SuppliedVec4(mesh, 2 * Turn, false);
  named->SetName("Tangents");
  vtkNew<vtkFloatArray> active, signs;
  active->SetName("T3");
  active->SetNumberOfComponents(3);
  signs->SetName("TangentSigns");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    active->InsertNextTuple3(std::cos(Turn), std::sin(Turn), 0.0);
    signs->InsertNextValue(1.0f);
  }
  mesh->GetPointData()->SetTangents(active);
  mesh->GetPointData()->AddArray(signs);
  SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID, "");
  run.Update();
  EXPECT_EQ(0, run.Filter->GetNumberOfReplacedTangents());
  EXPECT_TRUE(HasFrame(run, 0, { std::cos(Turn), std::sin(Turn), 0.0, 1.0 }));
}

TEST(TangentFramesSupplied, KeptSignsFollowTheOutputConvention)
{
  // glTF-convention input (v down) with correct glTF signs: MikkTSpace's output convention is
  // glTF's, so the signs are kept; the weighted methods' signs follow the stored v-down
  // coordinates, the opposite, so kept signs are written negated to match their neighbours.
  auto mesh = Plane(false);
  auto supplied = SuppliedVec4(mesh, 0.0, false);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    supplied->SetComponent(p, 3, -1.0); // glTF's w for v-down coordinates of this plane
  }
  for (int method :
    { vtkPolyDataTangentFrames::MIKKTSPACE, vtkPolyDataTangentFrames::ANGLE_WEIGHTED })
  {
    SuppliedRun run(mesh, vtkPolyDataTangentFrames::KEEP_VALID);
    run.Filter->SetMethod(method);
    run.Filter->GLTFSignConventionOn();
    run.Update();
    EXPECT_EQ(0, run.Filter->GetNumberOfReplacedTangents());
    SuppliedRun recompute(mesh, vtkPolyDataTangentFrames::RECOMPUTE);
    recompute.Filter->SetMethod(method);
    recompute.Filter->GLTFSignConventionOn();
    recompute.Update();
    EXPECT_EQ(recompute.Frame(0)[3], run.Frame(0)[3])
      << vtkPolyDataTangentFrames::GetMethodName(method);
  }
}

TEST(TangentFramesSupplied, AnErrorPassesTheInputThroughUnchanged)
{
  // A triangle with a point id out of range: an error and pass-through in both keeping modes,
  // with KEEP_VALID (one sign wrong, so that frames are computed) and with KEEP, which computes
  // no frame here (every supplied value is finite). The input's own Tangents / TangentSigns
  // (3 + 1 components) come through unchanged.
  auto mesh = Plane(false);
  auto vec4 = SuppliedVec4(mesh, 0.0, false);
  vtkNew<vtkFloatArray> tangents, signs;
  tangents->SetName("Tangents");
  tangents->SetNumberOfComponents(3);
  signs->SetName("TangentSigns");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    tangents->InsertNextTuple3(1.0, 0.0, 0.0);
    signs->InsertNextValue(p == 0 ? -1.0 : 1.0);
  }
  mesh->GetPointData()->SetTangents(tangents);
  mesh->GetPointData()->AddArray(signs);
  const vtkIdType bad[3] = { 0, 1, 1000 };
  mesh->GetPolys()->InsertNextCell(3, bad);
  for (int mode : { vtkPolyDataTangentFrames::KEEP_VALID, vtkPolyDataTangentFrames::KEEP })
  {
    for (int method :
      { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetSuppliedTangentsName(mode)) + " " +
        vtkPolyDataTangentFrames::GetMethodName(method));
      SuppliedRun run(mesh, mode, "");
      run.Filter->SetMethod(method);
      run.Filter->GLTFSignConventionOn(); // kept signs would be negated for the weighted method
      run.Update();
      EXPECT_TRUE(run.Messages->GetError());
      EXPECT_NE(std::string::npos, run.Messages->GetErrorMessage().find("point id outside"));
      // The input passes through: its own arrays, not frames written over them.
      EXPECT_EQ(tangents.Get(), run.Output->GetPointData()->GetTangents());
      EXPECT_EQ(signs.Get(), run.Output->GetPointData()->GetArray("TangentSigns"));
      EXPECT_EQ(-1.0, signs->GetValue(0));
      EXPECT_EQ(1.0, signs->GetValue(1));
      EXPECT_EQ(
        mesh->GetPointData()->GetNumberOfArrays(), run.Output->GetPointData()->GetNumberOfArrays());
    }
  }
}

TEST(TangentFramesSupplied, CompositeInputSumsTheCountsOverTheBlocks)
{
  vtkNew<vtkMultiBlockDataSet> blocks;
  for (unsigned int b = 0; b < 2; ++b)
  {
    auto mesh = Plane(false);
    auto supplied = SuppliedVec4(mesh, Turn, false);
    supplied->SetComponent(b, 3, -1.0); // one flipped w per block
    blocks->SetBlock(b, mesh);
  }
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(blocks);
  filter->SetSuppliedTangentsToKeepValid();
  filter->SetSuppliedTangentsArrayName("TANGENT");
  filter->Update();
  EXPECT_EQ(2, filter->GetNumberOfReplacedTangents());
  EXPECT_EQ(2, filter->GetNumberOfWrongSignTangents());
  auto* out = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(nullptr, out);
  for (unsigned int b = 0; b < 2; ++b)
  {
    auto* block = vtkPolyData::SafeDownCast(out->GetBlock(b));
    ASSERT_NE(nullptr, block);
    EXPECT_EQ(1.0, block->GetPointData()->GetArray("TangentSigns")->GetComponent(b, 0));
  }
}
