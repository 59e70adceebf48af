// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMappedSurfaceRepresentation.h"

#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactory.h"
#include "vtkTexture.h"

vtkStandardNewMacro(vtkNormalMappedSurfaceRepresentation);

vtkNormalMappedSurfaceRepresentation::vtkNormalMappedSurfaceRepresentation()
{
  // The superclass made ParaView's composite mappers; ours replace them, and SetupDefaults
  // connects the new ones into the representation's pipeline as it did the old.
  this->Mapper->Delete();
  this->LODMapper->Delete();
  this->Mapper = vtkNormalMapCompositePolyDataMapper::New();
  this->LODMapper = vtkNormalMapCompositePolyDataMapper::New();
  this->SetupDefaults();
}

vtkNormalMappedSurfaceRepresentation::~vtkNormalMappedSurfaceRepresentation() = default;

vtkNormalMapCompositePolyDataMapper* vtkNormalMappedSurfaceRepresentation::NormalMapper(
  int which) const
{
  return static_cast<vtkNormalMapCompositePolyDataMapper*>(
    which == 0 ? this->Mapper : this->LODMapper);
}

void vtkNormalMappedSurfaceRepresentation::SetMapEncoding(int encoding)
{
  for (int which : { 0, 1 })
  {
    this->NormalMapper(which)->SetMapEncoding(encoding);
  }
  this->Modified();
}

void vtkNormalMappedSurfaceRepresentation::SetFrameSource(int source)
{
  for (int which : { 0, 1 })
  {
    this->NormalMapper(which)->SetFrameSource(source);
  }
  this->Modified();
}

void vtkNormalMappedSurfaceRepresentation::SetTangentSignsArray(const char* name)
{
  const std::string signs = name && *name ? name : "TangentSigns";
  for (int which : { 0, 1 })
  {
    this->NormalMapper(which)->SetTangentSignsArrayName(signs);
  }
  this->Modified();
}

void vtkNormalMappedSurfaceRepresentation::SetNormalTexture(vtkTexture* texture)
{
  this->ParaViewNormalTexture = texture;
  this->ApplyNormalTexture();
}

void vtkNormalMappedSurfaceRepresentation::SetNormalMapTexture(vtkTexture* texture)
{
  this->NormalMapTexture = texture;
  this->ApplyNormalTexture();
}

void vtkNormalMappedSurfaceRepresentation::ApplyNormalTexture()
{
  vtkTexture* texture =
    this->NormalMapTexture ? this->NormalMapTexture : this->ParaViewNormalTexture;
  // The representation draws normal maps with trilinear filtering (mipmaps), so that a map seen
  // from afar does not alias; the mapper itself leaves textures as they are set up.
  if (texture && texture->GetInterpolate())
  {
    texture->MipmapOn();
  }
  this->Superclass::SetNormalTexture(texture);
}

void vtkNormalMappedSurfaceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto* mapper = this->NormalMapper(0);
  os << indent
     << "MapEncoding: " << vtkNormalMapPolyDataMapper::GetMapEncodingName(mapper->GetMapEncoding())
     << "\n";
  os << indent
     << "FrameSource: " << vtkNormalMapPolyDataMapper::GetFrameSourceName(mapper->GetFrameSource())
     << "\n";
  os << indent << "TangentSignsArray: " << mapper->GetTangentSignsArrayName() << "\n";
  os << indent << "NormalMapTexture: " << this->NormalMapTexture.GetPointer() << "\n";
}
