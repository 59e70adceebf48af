// One view per setting of the mapper. Top row: the four encodings of one bricks map on a quad
// (OpenGL, DirectX, two-channel, object space), the derivative frame on a quad without
// tangents, and the quad seen from the back with two-sided lighting (bevels still lit from the
// light's side). Bottom row: strength 0, 0.5 and 1, a torus with mirrored UVs (bricks), a
// sphere scaled (1.6, 0.6, 1) and the mirrored torus with rivets.
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;

struct View
{
  vtkPolyData* Mesh;
  vtkTexture* Texture;
  int Encoding = Mapper::TANGENT_SPACE_OPENGL;
  int FrameSource = Mapper::AUTOMATIC;
  double Strength = 1.0;
  double Scale[3] = { 1.0, 1.0, 1.0 };
  double RotateX = 0.0, RotateY = 0.0;
};

void AddView(vtkRenderWindow* window, int column, int row, const View& view)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(column / 6.0, (1 - row) / 2.0, (column + 1) / 6.0, (2 - row) / 2.0);
  renderer->SetBackground(0.1, 0.1, 0.12);
  renderer->SetTwoSidedLighting(true);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(-1.0, 1.5, 2.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->AddLight(light);
  vtkNew<Mapper> mapper;
  mapper->SetInputData(view.Mesh);
  mapper->SetMapEncoding(view.Encoding);
  mapper->SetFrameSource(view.FrameSource);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(view.Scale[0], view.Scale[1], view.Scale[2]);
  actor->RotateX(view.RotateX);
  actor->RotateY(view.RotateY);
  vtkProperty* property = actor->GetProperty();
  property->SetNormalTexture(view.Texture);
  property->SetNormalScale(view.Strength);
  property->SetColor(0.8, 0.55, 0.4);
  property->SetSpecular(0.4);
  property->SetSpecularPower(30.0);
  property->SetInterpolationToPhong();
  renderer->AddActor(actor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.4);
  window->AddRenderer(renderer);
}
}

int TestNormalMapSettings(int argc, char* argv[])
{
  using nmtest::Pattern;
  using nmtest::Storage;
  auto texture = [](Pattern p, Storage s)
  { return nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(p, 256, s)); };
  auto openGL = texture(Pattern::Bricks, Storage::OpenGL);
  auto directX = texture(Pattern::Bricks, Storage::DirectX);
  auto twoChannel = texture(Pattern::Bricks, Storage::TwoChannel);
  auto rivets = texture(Pattern::Rivets, Storage::OpenGL);
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  auto bareQuad = nmtest::MakeQuad(4);
  vtkNormalMapping::TorusOptions options;
  options.U = 96;
  options.V = 48;
  options.MirrorU = true;
  auto mirroredTorus = nmtest::WithTangents(vtkNormalMapping::MakeTorus(options));
  auto sphere = nmtest::WithTangents(nmtest::MakeSphere(48));

  auto window = nmtest::MakeWindow(900, 300);
  View v{ quad, openGL };
  AddView(window, 0, 0, v);
  v.Texture = directX;
  v.Encoding = Mapper::TANGENT_SPACE_DIRECTX;
  AddView(window, 1, 0, v);
  v.Texture = twoChannel;
  v.Encoding = Mapper::TWO_CHANNEL_OPENGL;
  AddView(window, 2, 0, v);
  v.Texture = openGL; // on this quad the object-space map holds the same texels
  v.Encoding = Mapper::OBJECT_SPACE;
  AddView(window, 3, 0, v);
  View d{ bareQuad, openGL };
  d.FrameSource = Mapper::SCREEN_DERIVATIVES;
  AddView(window, 4, 0, d);
  View back{ quad, openGL };
  back.RotateY = 180.0; // the quad's back faces the camera
  AddView(window, 5, 0, back);

  for (int i = 0; i < 3; ++i)
  {
    View s{ quad, rivets };
    s.Strength = 0.5 * i;
    AddView(window, i, 1, s);
  }
  View torus{ mirroredTorus, openGL };
  torus.RotateX = -50.0;
  AddView(window, 3, 1, torus);
  View scaled{ sphere, rivets };
  scaled.Scale[0] = 1.6;
  scaled.Scale[1] = 0.6;
  scaled.RotateX = -60.0;
  AddView(window, 4, 1, scaled);
  View mirroredRivets{ mirroredTorus, rivets };
  mirroredRivets.RotateX = -50.0;
  AddView(window, 5, 1, mirroredRivets);
  window->Render();
  nmtest::ReportRenderPath(window);
  return nmtest::CompareWithBaseline(window, argc, argv);
}
