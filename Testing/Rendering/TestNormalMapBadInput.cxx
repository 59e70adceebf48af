// What the mapper does with input it cannot use as asked: it renders, warns once per actor and
// reason (through VTK's warning events), and draws without the map where the map cannot apply.
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkNormalMapObjectFactory.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <iostream>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;

/// One actor with our mapper in a window that stays open across renders.
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window = nmtest::MakeWindow(128, 128);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<Mapper> NormalMapper;
  vtkNew<vtkActor> Actor;
  std::vector<std::string> Warnings;

  Scene(vtkPolyData* mesh, vtkTexture* texture)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(-1.0, 1.5, 2.0);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    this->Renderer->AddLight(light);
    this->NormalMapper->SetInputData(mesh);
    vtkNew<vtkCallbackCommand> onWarning;
    onWarning->SetClientData(&this->Warnings);
    onWarning->SetCallback(
      [](vtkObject*, unsigned long, void* clientData, void* callData)
      {
        static_cast<std::vector<std::string>*>(clientData)
          ->emplace_back(static_cast<char*>(callData));
      });
    this->NormalMapper->AddObserver(vtkCommand::WarningEvent, onWarning);
    this->Actor->SetMapper(this->NormalMapper);
    if (texture)
    {
      this->Actor->GetProperty()->SetNormalTexture(texture);
    }
    this->Actor->GetProperty()->SetSpecular(0.3);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->GetActiveCamera()->SetPosition(0.0, 0.0, 5.0);
    this->Renderer->ResetCameraClippingRange();
    this->Window->AddRenderer(this->Renderer);
  }

  std::vector<unsigned char> Render()
  {
    this->Window->Render();
    return nmtest::ReadPixels(this->Window);
  }

  bool Warned(const std::string& text) const
  {
    int count = 0;
    for (const auto& w : this->Warnings)
    {
      count += w.find(text) != std::string::npos ? 1 : 0;
    }
    return count == 1;
  }
};

bool Same(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int bound)
{
  const auto d = nmtest::Compare(a, b, nmtest::CoveredPixels(a, b), bound);
  return d.Compared > 0 && d.WithinFraction == 1.0;
}
}

int TestNormalMapBadInput(int, char*[])
{
  nmtest::Checks check;
  using nmtest::Pattern;
  using nmtest::Storage;
  auto texture =
    nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(Pattern::Rivets, 64, Storage::OpenGL));
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(2));
  const auto unmapped = Scene(quad, nullptr).Render();
  const auto mapped = Scene(quad, texture).Render();
  check(!Same(unmapped, mapped, 0), "the map changes the image (control)");

  { // No texture coordinates: drawn without the map, one warning over several renders.
    auto bare = vtkSmartPointer<vtkPolyData>::New();
    bare->DeepCopy(quad);
    bare->GetPointData()->SetTCoords(nullptr);
    bare->GetPointData()->RemoveArray("TCoords");
    Scene scene(bare, texture);
    const auto first = scene.Render();
    scene.Render();
    check(scene.Warned("no texture coordinates") && scene.Warnings.size() == 1,
      "no texture coordinates: one warning");
    check(
      scene.NormalMapper->GetLastAppliedFrame() == Mapper::NOT_APPLIED && Same(first, unmapped, 0),
      "no texture coordinates: drawn without the map");
  }
  { // A one-channel image is a height map, not a normal map.
    Scene scene(quad,
      nmtest::MakeNormalTexture(
        nmtest::MakeNormalMapImage(Pattern::Rivets, 64, Storage::OneChannel)));
    const auto pixels = scene.Render();
    check(scene.Warned("1 channel(s)"), "one-channel texture: one warning");
    check(Same(pixels, unmapped, 0), "one-channel texture: drawn without the map");
  }
  { // sRGB: warned, encoded back to the stored values. The GPU filters the decoded (linear)
    // values, so between texels the re-encoded value is not the interpolation of the stored
    // ones; where neighbouring texels differ most (the rivets' rims) that shows: 3 levels
    // (measured: max 3, 99.3% within 2).
    auto srgb =
      nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(Pattern::Rivets, 64, Storage::OpenGL));
    Scene scene(quad, srgb);
    // vtkProperty refuses an sRGB normal texture, but the flag can be turned on afterwards.
    srgb->UseSRGBColorSpaceOn();
    const auto pixels = scene.Render();
    check(scene.Warned("sRGB"), "sRGB texture: one warning");
    check(Same(pixels, mapped, 3), "sRGB texture: rendered like the linear one");
  }
  { // Three-component tangents without signs (VTK's own filter): sign +1, one warning.
    auto unsigned3 = vtkSmartPointer<vtkPolyData>::New();
    unsigned3->DeepCopy(quad);
    unsigned3->GetPointData()->RemoveArray("TangentSigns");
    Scene scene(unsigned3, texture);
    const auto pixels = scene.Render();
    check(scene.Warned("no handedness sign"), "unsigned tangents: one warning");
    check(scene.NormalMapper->GetLastAppliedFrame() == Mapper::APPLIED_UNSIGNED_TANGENTS &&
        Same(pixels, mapped, 0),
      "unsigned tangents on an unmirrored quad: the same image");
  }
  { // glTF-style 4-component double tangents (sign in w): no warning, the same image.
    auto gltf = vtkSmartPointer<vtkPolyData>::New();
    gltf->DeepCopy(quad);
    vtkDataArray* t = quad->GetPointData()->GetArray("Tangents");
    vtkDataArray* s = quad->GetPointData()->GetArray("TangentSigns");
    vtkNew<vtkDoubleArray> t4;
    t4->SetName("TANGENT");
    t4->SetNumberOfComponents(4);
    for (vtkIdType i = 0; i < t->GetNumberOfTuples(); ++i)
    {
      const double* v = t->GetTuple3(i);
      t4->InsertNextTuple4(v[0], v[1], v[2], s->GetTuple1(i));
    }
    // VTK's Tangents attribute must have 3 components, so a 4-component array goes by name.
    gltf->GetPointData()->RemoveArray("TangentSigns");
    gltf->GetPointData()->RemoveArray("Tangents");
    gltf->GetPointData()->AddArray(t4);
    Scene scene(gltf, texture);
    scene.NormalMapper->SetTangentsArrayName("TANGENT");
    const auto pixels = scene.Render();
    check(scene.Warnings.empty() &&
        scene.NormalMapper->GetLastAppliedFrame() == Mapper::APPLIED_POINT_TANGENTS,
      "4-component double tangents: used with their sign, no warning");
    check(Same(pixels, mapped, 1), "4-component double tangents: the same image");
  }
  { // Point tangents asked for but absent: warned, derivative frame.
    auto bare = nmtest::MakeQuad(2);
    Scene scene(bare, texture);
    scene.NormalMapper->SetFrameSource(Mapper::POINT_TANGENTS);
    const auto pixels = scene.Render();
    check(scene.Warned("no tangent array"), "missing tangents: one warning");
    check(scene.NormalMapper->GetLastAppliedFrame() == Mapper::APPLIED_DERIVATIVES &&
        Same(pixels, mapped, 2),
      "missing tangents: derivative frame, the same image");
  }
  { // Changes between renders: frame source, texture removed and restored, a 1x1 map, empty
    // input. Each render is right for the state at that time.
    Scene scene(quad, texture);
    scene.Render();
    scene.NormalMapper->SetFrameSource(Mapper::SCREEN_DERIVATIVES);
    const auto derivatives = scene.Render();
    check(scene.NormalMapper->GetLastAppliedFrame() == Mapper::APPLIED_DERIVATIVES &&
        Same(derivatives, mapped, 2),
      "frame source switched to derivatives between renders");
    scene.NormalMapper->SetFrameSource(Mapper::AUTOMATIC);
    scene.Actor->GetProperty()->RemoveTexture("normalTex");
    check(Same(scene.Render(), unmapped, 0), "texture removed: drawn without the map");
    scene.Actor->GetProperty()->SetNormalTexture(texture);
    check(Same(scene.Render(), mapped, 0), "texture restored: the map again");
    auto tiny =
      nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(Pattern::SineBump, 1, Storage::OpenGL));
    scene.Actor->GetProperty()->SetNormalTexture(tiny);
    const auto oneTexel = scene.Render();
    check(!oneTexel.empty(), "1x1 normal map renders");
    scene.NormalMapper->SetInputData(vtkNew<vtkPolyData>());
    scene.Render();
    check(scene.Warnings.empty(), "none of these warned");
  }
  { // The object factory: opt-in, reversible.
    auto before = vtk::TakeSmartPointer(vtkPolyDataMapper::New());
    vtkNormalMapObjectFactory::Install();
    auto during = vtk::TakeSmartPointer(vtkPolyDataMapper::New());
    vtkNormalMapObjectFactory::Uninstall();
    auto after = vtk::TakeSmartPointer(vtkPolyDataMapper::New());
    check(!Mapper::SafeDownCast(before) && Mapper::SafeDownCast(during) &&
        !Mapper::SafeDownCast(after) && !vtkNormalMapObjectFactory::IsInstalled(),
      "object factory: Install makes vtkPolyDataMapper::New() ours, Uninstall undoes it");
  }
  return check.Result();
}
