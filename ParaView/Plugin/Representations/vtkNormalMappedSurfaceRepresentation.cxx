// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMappedSurfaceRepresentation.h"

#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkInformationVector.h"
#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkTexture.h"

vtkStandardNewMacro(vtkNormalMappedSurfaceRepresentation);

vtkNormalMappedSurfaceRepresentation::vtkNormalMappedSurfaceRepresentation()
{
  // The superclass made ParaView's composite mappers; ours replace them, and SetupDefaults
  // connects the new ones into the representation's pipeline as it did the old. They keep the
  // names of the id arrays that ParaView's selection reads.
  for (vtkMapper** mapper : { &this->Mapper, &this->LODMapper })
  {
    auto* ours = vtkNormalMapCompositePolyDataMapper::New();
    if (auto* previous = vtkCompositePolyDataMapper2::SafeDownCast(*mapper))
    {
      ours->SetPointIdArrayName(previous->GetPointIdArrayName());
      ours->SetCellIdArrayName(previous->GetCellIdArrayName());
      ours->SetCompositeIdArrayName(previous->GetCompositeIdArrayName());
      ours->SetProcessIdArrayName(previous->GetProcessIdArrayName());
    }
    (*mapper)->Delete();
    *mapper = ours;
  }
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
  // Empty: no sign array, so that a user can choose unsigned tangents.
  for (int which : { 0, 1 })
  {
    this->NormalMapper(which)->SetTangentSignsArrayName(name ? name : "");
  }
  this->Modified();
}

void vtkNormalMappedSurfaceRepresentation::SetTangentsArray(const char* name)
{
  // Not the superclass's SetTangentArray: it would make the array the active tangents at every
  // update, which VTK refuses for 4 components with a warning. RequestData decides, seeing the
  // data.
  this->TangentsArrayName = name ? name : "";
  for (int which : { 0, 1 })
  {
    this->NormalMapper(which)->SetTangentsArrayName(this->TangentsArrayName);
  }
  this->MarkModified();
}

int vtkNormalMappedSurfaceRepresentation::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The mappers read the tangents by name (SetTangentsArray), so ParaView is given no name to
  // make the active tangents.
  this->MultiBlockMaker->SetInputArrayToProcess(
    2, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "");
  const int result = this->Superclass::RequestData(request, inputVector, outputVector);
  // Nor does the geometry the view delivers keep the input's active tangents, where a name is
  // set: VTK's legacy data writer, which carries the geometry from pvserver to a client that
  // renders it, writes every attribute but the tangents and so drops them; a plain array
  // travels.
  if (!this->TangentsArrayName.empty())
  {
    for (vtkDataSet* block :
      vtkCompositeDataSet::GetDataSets(this->MultiBlockMaker->GetOutputDataObject(0)))
    {
      block->GetPointData()->SetActiveAttribute(-1, vtkDataSetAttributes::TANGENTS);
    }
  }
  return result;
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

void vtkNormalMappedSurfaceRepresentation::SetNormalScale(double scale)
{
  this->ParaViewNormalScale = scale;
  this->ApplyNormalScale();
}

void vtkNormalMappedSurfaceRepresentation::SetNormalMapScale(double scale)
{
  this->NormalMapScale = scale;
  this->ApplyNormalScale();
}

void vtkNormalMappedSurfaceRepresentation::ApplyNormalTexture()
{
  // The superclass sets the texture's filtering from the representation's Interpolate Textures
  // and Use Mipmap Textures, as for ParaView's own textures.
  this->Superclass::SetNormalTexture(
    this->NormalMapTexture ? this->NormalMapTexture : this->ParaViewNormalTexture);
  this->ApplyNormalScale();
}

void vtkNormalMappedSurfaceRepresentation::ApplyNormalScale()
{
  this->Superclass::SetNormalScale(
    this->NormalMapTexture ? this->NormalMapScale : this->ParaViewNormalScale);
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
  os << indent << "TangentsArrayName: " << mapper->GetTangentsArrayName() << "\n";
  os << indent << "TangentSignsArray: " << mapper->GetTangentSignsArrayName() << "\n";
  os << indent << "NormalMapTexture: " << this->NormalMapTexture.GetPointer() << "\n";
  os << indent << "NormalMapScale: " << this->NormalMapScale << "\n";
}
