// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPolyDataTangentFrames
 * @brief   per-point tangent frames (tangent, handedness sign, bitangent) from texture coordinates
 *
 * Needs polydata with point texture coordinates (the active TCoords, or the array named with
 * SetTCoordsArrayName) and, preferably, point normals. For every triangle it solves
 * E1 = du1 T + dv1 B, E2 = du2 T + dv2 B, then sums the triangle tangents around each point
 * with the chosen weighting (see vtkNormalMapping::TangentMethod), removes the component along
 * the point normal (Gram-Schmidt) and normalizes.
 *
 * Outputs (point data, in the output precision):
 * - `Tangents` (3 components, set as the TANGENTS attribute): unit, perpendicular to the normal.
 * - `TangentSigns` (1 component): +1 or -1, the handedness in the glTF / MikkTSpace convention
 *   bitangent = sign * cross(N, T). Points whose triangles have mirrored UVs get -1.
 * - `Bitangents` (3 components), when ComputeBitangents is on: sign * cross(N, T).
 * - `Tangents` in cell data (3 components) when ComputeCellTangents is on: the tangent of each
 *   polygon or strip, perpendicular to its geometric normal; (0, 0, 0) for vertex and line cells.
 * - `Normals`, when the input had no point normals and the filter computed them.
 *
 * Mirror seams: a point whose triangles disagree on handedness cannot hold both frames. With
 * Splitting on (the default) such a point is duplicated with all its point data, and the
 * cells on its mirrored (-1) side are re-pointed to the copy; the copies are appended after
 * the input points and the cells keep their order. A strip crossing a seam, or a polygon folded
 * in UV, has triangles of both sides at one corner: it is replaced, in place, by its triangles,
 * each with the cell's cell data, at the cost of a second run. With Splitting off the point takes
 * the frame of the side with the larger total weight and is counted in NumberOfHandednessConflicts.
 *
 * Cells: triangles, polygons (fan-triangulated on the fly: corner 0 with i, i+1) and triangle
 * strips give frames; vertex and line cells pass through untouched.
 *
 * Degenerate input never produces NaN or Inf. Triangles with zero UV area or zero area (within a
 * few epsilons of the stored precision, see vtkNormalMapping::DegeneracyTolerance), with a
 * height within the rounding noise of their coordinates (vtkNormalMapping::IsRoundingNoise),
 * or with non-finite coordinates contribute nothing and are counted (NumberOfDegenerateTriangles).
 * A point with no usable triangle (a "fallback" point) takes the mean of its neighbours' tangents
 * projected onto its tangent plane, or where that fails a fixed rule (the Duff et al. basis of
 * the normal), and the majority sign of its neighbours (+1 if none); they are counted in
 * NumberOfFallbackPoints.
 *
 * Bad input is reported and never crashes: missing or non-numeric texture coordinates, point
 * ids out of range, arrays shorter than the point count, or a malformed cell array (offsets
 * that do not start at 0, decrease, or do not end at the connectivity size) are errors, and
 * the output is the input passed through; missing normals are computed (area-weighted, without
 * splitting) with a warning; cell normals alone are averaged to points with a warning; texture
 * coordinates with 1 or more than 2 components use (u, 0) or the first two with a warning.
 *
 * Supplied tangents (SuppliedTangents, default RECOMPUTE: they are ignored): KEEP and
 * KEEP_VALID read the input's tangents (a 4-component array whose w is the sign, or 3
 * components plus the point array `TangentSigns`; see SetSuppliedTangentsArrayName), which need
 * point normals to be meaningful. KEEP writes them to the outputs as they are, computing no
 * frame (only points with non-finite values, or values too large for the output's precision,
 * which would put NaN or infinity in the output, get computed frames). KEEP_VALID checks every
 * point's frame (vtkTangentFrameChecks.h: finite, unit, perpendicular to the normal, sign +1 or
 * -1 and agreeing with the UV winding of all the point's triangles, by FrameCheckTolerances) and
 * gives the points that fail the frame of the selected Method; the others keep theirs. Points whose
 * triangles have both windings (a mirror seam whose point is shared) fail, as one sign cannot suit
 * both sides: with Splitting they are split like any seam point, and the kept points never are (a
 * kept point that the method would have split gives its copies its supplied frame too). Kept signs
 * are written as +1 or -1 in the output's convention: for the weighted methods with
 * GLTFSignConvention on (whose signs follow the v-down coordinates as stored) that is the opposite
 * of glTF's w. Without usable supplied arrays or without point normals the filter warns and
 * computes every frame.
 *
 * Composite input (a multiblock from a reader, for example) gives output of the same structure:
 * every polydata block gets its frames as if it were filtered alone, and the counts below are the
 * sums over the blocks. Blocks that are not polydata, and polydata blocks without the texture
 * coordinates, pass through with a warning that names the block (a scene's untextured parts are
 * not an error).
 *
 * The work runs on vtkSMPTools and is deterministic: the output is bit-identical for any number
 * of threads, because each point adds its triangles in triangle order, whatever thread computed
 * them. Progress is reported and AbortExecute honoured between parallel passes; an aborted
 * execution leaves an empty output.
 */
#ifndef vtkPolyDataTangentFrames_h
#define vtkPolyDataTangentFrames_h

#include "vtkNormalMappingModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For TCoordsArrayName
#include <vector> // For BlockInput

class vtkDataArray;

class VTKNORMALMAPPING_EXPORT vtkPolyDataTangentFrames : public vtkPolyDataAlgorithm
{
public:
  static vtkPolyDataTangentFrames* New();
  vtkTypeMacro(vtkPolyDataTangentFrames, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Values of Method (docs/filter.md, "Methods", says what each costs and gets right).
  enum Methods
  {
    /// The sum of the unit tangents of the point's triangles.
    UNWEIGHTED = 0,
    /// The same, each weighted by its triangle's area.
    AREA_WEIGHTED = 1,
    /// The same, each weighted by its triangle's angle at the point: independent of how a fan
    /// is split into triangles.
    ANGLE_WEIGHTED = 2,
    /// MikkTSpace-compatible frames (the tangents Blender, Substance, xNormal, Unity, Unreal
    /// and glTF bake normal maps against); see vtkMikkTSpaceKernel.h.
    MIKKTSPACE = 3,
  };

  ///@{
  /**
   * How the triangles around a point are weighted. Default ANGLE_WEIGHTED: independent of how a
   * fan is tessellated, at the cost of three corner angles per triangle.
   */
  vtkSetClampMacro(Method, int, UNWEIGHTED, MIKKTSPACE);
  vtkGetMacro(Method, int);
  void SetMethodToUnweighted() { this->SetMethod(UNWEIGHTED); }
  void SetMethodToAreaWeighted() { this->SetMethod(AREA_WEIGHTED); }
  void SetMethodToAngleWeighted() { this->SetMethod(ANGLE_WEIGHTED); }
  void SetMethodToMikkTSpace() { this->SetMethod(MIKKTSPACE); }
  static const char* GetMethodName(int method);
  ///@}

  ///@{
  /**
   * Name of the point array to read texture coordinates from. Empty (the default): the active
   * TCoords attribute. Use it to choose a second UV set.
   */
  void SetTCoordsArrayName(const std::string& name);
  const std::string& GetTCoordsArrayName() const { return this->TCoordsArrayName; }
  ///@}

  ///@{
  /// Duplicate points on mirror seams so both frames survive, cutting into triangles the strips
  /// and polygons that cross a seam at a corner (default on).
  vtkSetMacro(Splitting, bool);
  vtkGetMacro(Splitting, bool);
  vtkBooleanMacro(Splitting, bool);
  ///@}

  ///@{
  /**
   * Sign convention for texture coordinates whose v axis points down, as glTF's do (default
   * off: VTK's v-up convention). When on, the MikkTSpace method negates its signs so that
   * bitangent = sign * cross(N, T) matches glTF's TANGENT.w, and supplied signs are read in
   * glTF's convention (see SuppliedTangents): checked against the v-down coordinates, and kept
   * in the convention of the method's own signs.
   */
  vtkSetMacro(GLTFSignConvention, bool);
  vtkGetMacro(GLTFSignConvention, bool);
  vtkBooleanMacro(GLTFSignConvention, bool);
  ///@}

  /// Values of SuppliedTangents.
  enum SuppliedTangentsModes
  {
    /// Compute every frame; supplied tangents are ignored (pass through as point data).
    RECOMPUTE = 0,
    /// Use the supplied frames as they are (only non-finite ones are computed).
    KEEP = 1,
    /// Use the supplied frames that pass the checks; compute the others.
    KEEP_VALID = 2,
  };

  ///@{
  /// What to do with tangents the input already has (default RECOMPUTE); see the class comment.
  vtkSetClampMacro(SuppliedTangents, int, RECOMPUTE, KEEP_VALID);
  vtkGetMacro(SuppliedTangents, int);
  void SetSuppliedTangentsToRecompute() { this->SetSuppliedTangents(RECOMPUTE); }
  void SetSuppliedTangentsToKeep() { this->SetSuppliedTangents(KEEP); }
  void SetSuppliedTangentsToKeepValid() { this->SetSuppliedTangents(KEEP_VALID); }
  static const char* GetSuppliedTangentsName(int mode);
  ///@}

  ///@{
  /**
   * The point array of supplied tangents (3 or 4 components). Empty (the default): the active
   * tangents, else the point array `Tangents`.
   */
  void SetSuppliedTangentsArrayName(const std::string& name);
  const std::string& GetSuppliedTangentsArrayName() const
  {
    return this->SuppliedTangentsArrayName;
  }
  ///@}

  ///@{
  /// Also output point `Bitangents` = sign * cross(N, T) (default off).
  vtkSetMacro(ComputeBitangents, bool);
  vtkGetMacro(ComputeBitangents, bool);
  vtkBooleanMacro(ComputeBitangents, bool);
  ///@}

  ///@{
  /// Also output cell `Tangents` (default off).
  vtkSetMacro(ComputeCellTangents, bool);
  vtkGetMacro(ComputeCellTangents, bool);
  vtkBooleanMacro(ComputeCellTangents, bool);
  ///@}

  ///@{
  /**
   * Precision of the output arrays: vtkAlgorithm::DEFAULT_PRECISION (the default) follows the
   * input points (double points give double arrays, anything else float), SINGLE_PRECISION or
   * DOUBLE_PRECISION choose. The computation is in double whatever the input types.
   */
  vtkSetClampMacro(OutputPrecision, int, SINGLE_PRECISION, DEFAULT_PRECISION);
  vtkGetMacro(OutputPrecision, int);
  ///@}

  ///@{
  /// Counts from the last execution (summed over the blocks of composite input).
  /// Triangles (after fan-triangulating polygons and strips) with no usable frame.
  vtkGetMacro(NumberOfDegenerateTriangles, vtkIdType);
  /// Points with no usable triangle, given a frame from their neighbours or the fixed rule.
  /// For MIKKTSPACE: face corners MikkTSpace leaves at its default ((1, 0, 0), sign -1) or whose
  /// summed tangents cancel (sign kept); they get (1, 0, 0) made perpendicular to the normal.
  /// Points that keep their supplied frames (KEEP, KEEP_VALID), and their corners, are not
  /// counted.
  vtkGetMacro(NumberOfFallbackPoints, vtkIdType);
  /// Points whose triangles disagree on handedness (mirror seams); for MIKKTSPACE, points whose
  /// corners have different frames.
  vtkGetMacro(NumberOfHandednessConflicts, vtkIdType);
  /// Points added by splitting. For the weighted methods this equals
  /// NumberOfHandednessConflicts when Splitting is on; MikkTSpace can give a point more than two
  /// frames (UV seams, hard normals, several mirror groups), so it may add more.
  vtkGetMacro(NumberOfSplitPoints, vtkIdType);
  /// Points whose input normal was zero or non-finite: the weighted methods use the geometric
  /// normal there; MIKKTSPACE, like the reference, has no normal there (its bitangent is zero).
  vtkGetMacro(NumberOfInvalidNormals, vtkIdType);
  /// With KEEP or KEEP_VALID: supplied frames replaced by computed ones (input points; their
  /// split copies are not counted again).
  vtkGetMacro(NumberOfReplacedTangents, vtkIdType);
  /// With KEEP or KEEP_VALID, supplied frames found with each defect (a point may have several):
  /// a NaN or infinite value (or one too large for the output's precision); a tangent length off 1;
  /// a tangent not perpendicular to the normal; a sign that is not +1 or -1 or, with KEEP_VALID,
  /// disagrees with the UV winding of the point's triangles (or of some of them).
  vtkGetMacro(NumberOfNonFiniteTangents, vtkIdType);
  vtkGetMacro(NumberOfNonUnitTangents, vtkIdType);
  vtkGetMacro(NumberOfNonPerpendicularTangents, vtkIdType);
  vtkGetMacro(NumberOfWrongSignTangents, vtkIdType);
  ///@}

  /// Names of the arrays the filter writes.
  static const char* TangentsArrayName() { return "Tangents"; }
  static const char* SignsArrayName() { return "TangentSigns"; }
  static const char* BitangentsArrayName() { return "Bitangents"; }

protected:
  vtkPolyDataTangentFrames();
  ~vtkPolyDataTangentFrames() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  vtkTypeBool ProcessRequest(vtkInformation*,
    vtkInformationVector**,
    vtkInformationVector*) override;
  /// The output: polydata for polydata input, the input's own type for composite input.
  virtual int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  /**
   * For a piece of a partitioned mesh, one more level of ghost cells than asked for: a point's
   * frame needs every triangle around it, also on the piece's boundary. The extra ghost cells
   * stay in the output, marked as ghosts (vtkGhostType), as vtkPPolyDataNormals leaves them.
   */
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Method = ANGLE_WEIGHTED;
  std::string TCoordsArrayName;
  bool Splitting = true;
  bool GLTFSignConvention = false;
  bool ComputeBitangents = false;
  bool ComputeCellTangents = false;
  int OutputPrecision = DEFAULT_PRECISION;
  int SuppliedTangents = RECOMPUTE;
  std::string SuppliedTangentsArrayName;

  vtkIdType NumberOfDegenerateTriangles = 0;
  vtkIdType NumberOfFallbackPoints = 0;
  vtkIdType NumberOfHandednessConflicts = 0;
  vtkIdType NumberOfSplitPoints = 0;
  vtkIdType NumberOfInvalidNormals = 0;
  vtkIdType NumberOfReplacedTangents = 0;
  vtkIdType NumberOfNonFiniteTangents = 0;
  vtkIdType NumberOfNonUnitTangents = 0;
  vtkIdType NumberOfNonPerpendicularTangents = 0;
  vtkIdType NumberOfWrongSignTangents = 0;

private:
  vtkPolyDataTangentFrames(const vtkPolyDataTangentFrames&) = delete;
  void operator=(const vtkPolyDataTangentFrames&) = delete;

  /// Frames for one polydata; adds to the counts. Progress goes from progressBegin to
  /// progressEnd. `flatIndex`: the block's flat index in composite input, or -1.
  void ExecuteBlock(vtkPolyData* input,
    vtkPolyData* output,
    double progressBegin,
    double progressEnd,
    vtkIdType flatIndex);

  /// One polydata's inputs as ExecuteBlock checked them, and its share of the progress.
  struct BlockInput
  {
    vtkPolyData* Input = nullptr;
    vtkPolyData* Output = nullptr;
    vtkDataArray* UVs = nullptr;
    vtkDataArray* Normals = nullptr;     ///< usable point normals, or null
    vtkIdType UnusableNormals = 0;       ///< of those, the zero or non-finite ones
    vtkDataArray* CellNormals = nullptr; ///< averaged to points when Normals is null, or null
    bool PolysAreTriangles = false;
    /// Per point, non-zero where the caller keeps the point's supplied frame (KEEP,
    /// KEEP_VALID): such a point is never split nor counted as a conflict. Null: none.
    const unsigned char* KeptPoints = nullptr;
    double ProgressBegin = 0.0;
    double ProgressEnd = 1.0;
    /// When set, receives the input point that each point appended to the output copies (the
    /// split points' copies, in output order). Null: not asked for.
    std::vector<vtkIdType>* SplitSources = nullptr;
    /// When set (Splitting), receives the cells (over the polygons, then the strips) that hold a
    /// corner of a split point whose triangles need frames of both sides; the method then
    /// writes no output, and ComputeBlock runs it again with those cells cut into triangles.
    std::vector<vtkIdType>* MixedCells = nullptr;
  };

  /// The frames of one polydata whose inputs ExecuteBlock has checked.
  void ComputeBlock(const BlockInput& block);

  /// One run of the method on a block (ComputeBlock); returns the number of triangles it
  /// computed frames for.
  vtkIdType RunBlock(const BlockInput& block);

  /// Reports `fraction` of a block's execution as the filter's progress; false, with the
  /// block's output emptied, when the execution is to stop (AbortExecute).
  bool ContinueBlock(const BlockInput& block, double fraction);

  /// KEEP and KEEP_VALID (vtkPolyDataTangentFramesSupplied.cxx): the supplied frames, and
  /// ComputeBlock's for the points that need it.
  void ExecuteSupplied(const BlockInput& block);

  /// MIKKTSPACE (vtkPolyDataTangentFramesMikkTSpace.cxx) with these point normals: the input's,
  /// or ones ComputeBlock computed (`computedNormals`: the output carries them). Adds to the
  /// counts; returns the number of triangles the kernel made of the polygons and strips.
  vtkIdType ComputeMikkTSpace(const BlockInput& block, vtkDataArray* normals, bool computedNormals);

  /// Whether the output arrays are double (OutputPrecision and the input points decide).
  bool DoubleOutput(vtkPolyData* input) const;

  struct Internals;
  friend struct Internals;
};

#endif
