// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkNormalMappedSurfaceRepresentation
 * @brief   ParaView's surface representation, drawn through vtkNormalMapCompositePolyDataMapper.
 *
 * Everything ParaView's Surface representation does (it derives from the same class and keeps
 * its properties), with the front-face mappers replaced by the normal-mapping composite mapper:
 * - mirrored texture coordinates shade right: the handedness sign comes from the point array
 *   named by SetTangentSignsArray (what vtkPolyDataTangentFrames writes) or from the w of a
 *   4-component tangent array;
 * - a normal texture applies without a tangent array, with a frame from screen-space
 *   derivatives, and object-space maps need no frame at all;
 * - the map encodings of vtkNormalMapPolyDataMapper (OpenGL or DirectX green, two-channel,
 *   object space).
 *
 * The normal texture is ParaView's own NormalTexture (SetNormalTexture), whose panel widget is
 * enabled only for data with tangents, or this representation's SetNormalMapTexture, offered for
 * any data with texture coordinates. When both are set, SetNormalMapTexture's wins. The tangent
 * array is SetTangentsArray's, which the mappers read by name: 3 components, or 4 with the sign
 * in w (glTF's TANGENT), which ParaView cannot make the active tangents. ParaView's own
 * SetTangentArray is not read: the plugin's proxy copies its value into SetTangentsArray.
 * Each texture has its strength: ParaView's NormalScale, and SetNormalMapScale.
 *
 * The LOD mapper (interactive rendering of large data) is ours too. The back-face mappers
 * (ParaView's Backface Representation other than "Follow Frontface") stay ParaView's own.
 */
#ifndef vtkNormalMappedSurfaceRepresentation_h
#define vtkNormalMappedSurfaceRepresentation_h

#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkNormalMappingRepresentationsModule.h" // For export macro
#include "vtkSmartPointer.h"                       // For the textures

#include <string> // For the tangent array name

class vtkNormalMapCompositePolyDataMapper;

class VTKNORMALMAPPINGREPRESENTATIONS_EXPORT vtkNormalMappedSurfaceRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkNormalMappedSurfaceRepresentation* New();
  vtkTypeMacro(vtkNormalMappedSurfaceRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// vtkNormalMapPolyDataMapper::MapEncodings, forwarded to both mappers (full and LOD).
  void SetMapEncoding(int encoding);
  /// vtkNormalMapPolyDataMapper::FrameSources, forwarded to both mappers.
  void SetFrameSource(int source);
  /// Point array with the handedness signs (empty or null: none, the tangents are unsigned).
  void SetTangentSignsArray(const char* name);
  /// The point tangents: the mappers' TangentsArrayName (null or empty: the active tangents),
  /// 3 or 4 components. The rendered data has no active tangents where a name is set
  /// (RequestData).
  void SetTangentsArray(const char* name);
  /// ParaView's TangentArray, ignored: the proxy copies it into SetTangentsArray, and the
  /// superclass would make a 4-component array the active tangents, which VTK refuses.
  void SetTangentArray(const char*) override {}

  /// ParaView's NormalTexture property.
  void SetNormalTexture(vtkTexture* texture) override;
  /// This representation's normal texture, which needs no tangent array; wins over the above.
  void SetNormalMapTexture(vtkTexture* texture);
  /// ParaView's NormalScale property: the strength of its NormalTexture.
  void SetNormalScale(double scale) override;
  /// The strength of SetNormalMapTexture's texture (default 1).
  void SetNormalMapScale(double scale);

protected:
  vtkNormalMappedSurfaceRepresentation();
  ~vtkNormalMappedSurfaceRepresentation() override;

  /// Delivers the geometry without active tangents, so that they reach a client that renders.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkNormalMappedSurfaceRepresentation(const vtkNormalMappedSurfaceRepresentation&) = delete;
  void operator=(const vtkNormalMappedSurfaceRepresentation&) = delete;

  /// The full-resolution and the LOD mapper, both ours.
  vtkNormalMapCompositePolyDataMapper* NormalMapper(int which) const;
  /// Gives the actor's property the texture in effect (and its strength).
  void ApplyNormalTexture();
  /// Gives the actor's property the strength of the texture in effect.
  void ApplyNormalScale();

  std::string TangentsArrayName;
  vtkSmartPointer<vtkTexture> ParaViewNormalTexture;
  vtkSmartPointer<vtkTexture> NormalMapTexture;
  double ParaViewNormalScale = 1.0;
  double NormalMapScale = 1.0;
};

#endif
