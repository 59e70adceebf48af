// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapTangents.h"

#include "NormalMapFiles.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <string>
#include <vector>

namespace NormalMapTangents
{
bool IsVDown(vtkPolyData* mesh)
{
  vtkDataArray* flag = mesh ? mesh->GetFieldData()->GetArray(VDownArrayName) : nullptr;
  return flag && flag->GetNumberOfTuples() > 0 && flag->GetComponent(0, 0) != 0;
}

void MarkVDown(vtkPolyData* mesh)
{
  vtkNew<vtkIntArray> flag;
  flag->SetName(VDownArrayName);
  flag->InsertNextValue(1);
  mesh->GetFieldData()->AddArray(flag);
}

void FlipToVUp(vtkPolyData* mesh)
{
  vtkPointData* pd = mesh->GetPointData();
  vtkDataArray* active = pd->GetTCoords();
  std::vector<vtkDataArray*> sets;
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* array = pd->GetArray(k);
    const char* name = array ? array->GetName() : nullptr;
    if (array &&
      (array == active ||
        (name && std::string(name).rfind("TEXCOORD_", 0) == 0 &&
          array->GetNumberOfComponents() == 2)))
    {
      sets.push_back(array);
    }
  }
  for (vtkDataArray* uv : sets)
  {
    auto flipped = vtk::TakeSmartPointer(uv->NewInstance());
    flipped->DeepCopy(uv);
    for (vtkIdType i = 0; i < uv->GetNumberOfTuples(); ++i)
    {
      flipped->SetComponent(i, 1, 1.0 - uv->GetComponent(i, 1));
    }
    if (uv == active)
    {
      pd->SetTCoords(flipped); // replaces the array of its name
    }
    else
    {
      pd->AddArray(flipped); // replaces the array of its name, in its place
    }
  }
  // The mark goes from this mesh only, not from meshes that share its field data.
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(mesh->GetFieldData());
  fields->RemoveArray(VDownArrayName);
  mesh->SetFieldData(fields);
}

void Counts::Add(const Counts& other)
{
  this->InputPoints += other.InputPoints;
  this->OutputPoints += other.OutputPoints;
  this->Triangles += other.Triangles;
  this->SplitPoints += other.SplitPoints;
  this->DegenerateTriangles += other.DegenerateTriangles;
  this->FallbackPoints += other.FallbackPoints;
  this->InvalidNormals += other.InvalidNormals;
  this->ReplacedTangents += other.ReplacedTangents;
}

vtkDataArray* FindTCoords(vtkPolyData* mesh, const std::string& name)
{
  vtkPointData* pd = mesh->GetPointData();
  vtkDataArray* uv = name.empty() ? pd->GetTCoords() : pd->GetArray(name.c_str());
  if (!uv || uv->GetNumberOfComponents() < 2 || uv->GetNumberOfTuples() < mesh->GetNumberOfPoints())
  {
    return nullptr;
  }
  return uv;
}

namespace
{
vtkIdType CountTriangles(vtkPolyData* mesh)
{
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
    {
      triangles += std::max<vtkIdType>(0, cells->GetCellSize(c) - 2);
    }
  }
  return triangles;
}
} // namespace

vtkSmartPointer<vtkPolyData> Compute(vtkPolyData* input,
  const Options& options,
  Counts& counts,
  std::vector<std::string>& warnings,
  std::string& error,
  const std::function<void(double)>& progress)
{
  if (!FindTCoords(input, options.TCoordsName))
  {
    error = options.TCoordsName.empty()
      ? std::string("the mesh has no texture coordinates")
      : "the mesh has no 2-component point array '" + options.TCoordsName + "'";
    return nullptr;
  }
  const bool vDown = options.VDown || IsVDown(input);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  filter->SetMethod(options.Method);
  filter->SetSplitting(options.Splitting);
  filter->SetTCoordsArrayName(options.TCoordsName);
  filter->SetGLTFSignConvention(vDown);
  filter->SetSuppliedTangents(options.SuppliedTangents);

  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(const_cast<std::function<void(double)>*>(&progress));
  observer->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      const auto* report = static_cast<const std::function<void(double)>*>(clientData);
      if (*report && callData)
      {
        (*report)(*static_cast<double*>(callData));
      }
    });
  filter->AddObserver(vtkCommand::ProgressEvent, observer);

  {
    NormalMapFiles::VTKMessageCapture messages;
    filter->Update();
    if (!messages.Errors().empty())
    {
      error = messages.Errors().front();
      return nullptr;
    }
    warnings.insert(warnings.end(), messages.Warnings().begin(), messages.Warnings().end());
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());

  // The filter's GLTFSignConvention negates only the MikkTSpace signs; the weighted methods
  // give the sign against dP/dv, which for v-down coordinates points to the image's bottom.
  if (vDown && options.Method != vtkPolyDataTangentFrames::MIKKTSPACE)
  {
    vtkDataArray* signs =
      output->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
    if (signs)
    {
      for (vtkIdType i = 0; i < signs->GetNumberOfTuples(); ++i)
      {
        signs->SetComponent(i, 0, -signs->GetComponent(i, 0));
      }
      signs->Modified();
    }
  }
  if (vDown && !IsVDown(output))
  {
    MarkVDown(output);
  }

  counts.InputPoints = input->GetNumberOfPoints();
  counts.OutputPoints = output->GetNumberOfPoints();
  counts.Triangles = CountTriangles(input);
  counts.SplitPoints = filter->GetNumberOfSplitPoints();
  counts.DegenerateTriangles = filter->GetNumberOfDegenerateTriangles();
  counts.FallbackPoints = filter->GetNumberOfFallbackPoints();
  counts.InvalidNormals = filter->GetNumberOfInvalidNormals();
  counts.ReplacedTangents = filter->GetNumberOfReplacedTangents();
  return output;
}
}
