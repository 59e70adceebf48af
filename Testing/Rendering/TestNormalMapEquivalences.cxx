// SPDX-License-Identifier: BSD-3-Clause
// Encodings, frame sources and strength that describe the same surface must render the same
// image, and the shader must hold only what each scene needs.
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h" // VTK_FLAT, VTK_GOURAUD, VTK_PBR
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <functional>
#include <iostream>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;

nmtest::Difference Between(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b,
  int bound)
{
  return nmtest::Compare(a, b, nmtest::CoveredPixels(a, b), bound);
}

void Report(const char* what, const nmtest::Difference& d, int bound)
{
  std::cout << what << ": " << d.Compared << " pixels, " << 100.0 * d.WithinFraction << "% within "
            << bound << " levels, max difference " << d.MaxChannel << std::endl;
}
}

int TestNormalMapEquivalences(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  const auto pattern = nmtest::Pattern::Rivets;
  auto image = [&](nmtest::Storage storage)
  { return nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(pattern, 128, storage)); };
  auto openGL = image(nmtest::Storage::OpenGL);
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(2));

  auto render = [&](vtkTexture* texture,
                  int encoding,
                  int frame,
                  double scale = 1.0,
                  bool stock = false,
                  std::string* shaders = nullptr,
                  int* applied = nullptr)
  {
    nmtest::FlatActor a;
    a.Mesh = quad;
    a.NormalTexture = texture;
    a.Encoding = encoding;
    a.FrameSource = frame;
    a.NormalScale = scale;
    a.StockMapper = stock;
    a.Shaders = shaders;
    a.AppliedFrame = applied;
    return nmtest::RenderFlat(setup, { a });
  };
  std::string shaders;
  int applied = -1;
  const auto reference =
    render(openGL, Mapper::TANGENT_SPACE_OPENGL, Mapper::AUTOMATIC, 1.0, false, &shaders, &applied);
  check(applied == Mapper::APPLIED_POINT_TANGENTS, "automatic frame with tangents: point tangents");
  check(shaders.find("nmTangentMC") != std::string::npos, "the tangent attribute is in the shader");

  // DirectX map (green stored negated) read as DirectX equals the OpenGL map read as OpenGL:
  // the decoded values are equal up to float rounding and the texels up to 8-bit rounding of
  // ties, so at most 1 level anywhere.
  {
    const auto directX =
      render(image(nmtest::Storage::DirectX), Mapper::TANGENT_SPACE_DIRECTX, Mapper::AUTOMATIC);
    const auto d = Between(reference, directX, 1);
    Report("DirectX map as DirectX vs OpenGL map as OpenGL", d, 1);
    check(d.WithinFraction == 1.0, "DirectX and OpenGL conventions agree");
  }
  // Two channels: z is rebuilt from 8-bit x and y instead of stored, which moves the normal by
  // up to ~half a level's worth of angle more: 2 levels, everywhere.
  {
    const auto twoChannel =
      render(image(nmtest::Storage::TwoChannel), Mapper::TWO_CHANNEL_OPENGL, Mapper::AUTOMATIC);
    const auto d = Between(reference, twoChannel, 2);
    Report("two-channel map vs RGB map", d, 2);
    check(d.WithinFraction == 1.0, "two-channel and RGB encodings agree");
  }
  // Object space: on this quad the tangent frame is the model's x, y, z, so the object-space
  // map holds the same texels; identical arithmetic up to float rounding: 1 level.
  {
    std::string objectShaders;
    int objectApplied = -1;
    const auto objectSpace = render(
      openGL, Mapper::OBJECT_SPACE, Mapper::AUTOMATIC, 1.0, false, &objectShaders, &objectApplied);
    const auto d = Between(reference, objectSpace, 1);
    Report("object-space vs tangent-space map", d, 1);
    check(d.WithinFraction == 1.0, "object-space and tangent-space encodings agree");
    check(objectApplied == Mapper::APPLIED_OBJECT_SPACE, "object-space path taken");
    check(objectShaders.find("nmTangentMC") == std::string::npos &&
        objectShaders.find("dFdx(tcoord") == std::string::npos,
      "object space: no tangent attribute, no derivative frame");
  }
  // Screen-space derivatives: the same frame up to the derivatives' float precision; 2 levels
  // on 99.9% of the pixels (2x2 quads at the rivets' rims see the steepest slopes).
  {
    std::string derivativeShaders;
    int derivativeApplied = -1;
    const auto derivatives = render(openGL,
      Mapper::TANGENT_SPACE_OPENGL,
      Mapper::SCREEN_DERIVATIVES,
      1.0,
      false,
      &derivativeShaders,
      &derivativeApplied);
    const auto d = Between(reference, derivatives, 2);
    Report("derivative frame vs point tangents", d, 2);
    check(d.WithinFraction >= 0.999, "derivative frame and point tangents agree");
    check(derivativeApplied == Mapper::APPLIED_DERIVATIVES, "derivative path taken");
    check(derivativeShaders.find("nmTangentMC") == std::string::npos,
      "derivative frame: no tangent attribute or varying");
  }
  // A transform of the texture coordinates (the actor's GeneralTextureTransform; ParaView's Flip
  // Textures is v' = 1 - v): the derivative frame differentiates the transformed coordinates,
  // and the point tangents must be turned to them. A flip of v and a quarter turn (u' = -v,
  // v' = u), under which the rivets look the same: both frame sources agree, as above (point
  // tangents that ignore the transform show the flipped rivets as dents). Tangents without signs
  // take the handedness of the untransformed coordinates (the flip mirrors the transformed ones),
  // so they give the image of the signed ones.
  {
    const double flip[16] = { 1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1 };
    const double turn[16] = { 0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    const auto unsignedQuad = nmtest::WithTangentLayout(quad, nmtest::TangentLayout::Unsigned);
    for (const double* transform : { flip, turn })
    {
      std::vector<unsigned char> images[3];
      for (int k = 0; k < 3; ++k)
      {
        nmtest::FlatActor a;
        a.Mesh = k == 2 ? unsignedQuad.Get() : quad.Get();
        a.NormalTexture = openGL;
        a.FrameSource = k == 1 ? Mapper::SCREEN_DERIVATIVES : Mapper::POINT_TANGENTS;
        a.TextureTransform = transform;
        images[k] = nmtest::RenderFlat(setup, { a });
      }
      const std::string what = transform == flip ? "flipped v" : "quarter-turned";
      const auto d = Between(images[0], images[1], 2);
      Report(("texture coordinates " + what + ": point tangents vs derivatives").c_str(), d, 2);
      check(d.WithinFraction >= 0.999,
        "texture coordinates " + what + ": point tangents and derivative frame agree");
      const auto u = Between(images[0], images[2], 0);
      Report(("texture coordinates " + what + ": signed vs unsigned tangents").c_str(), u, 0);
      check(u.WithinFraction == 1.0,
        "texture coordinates " + what + ": unsigned tangents give the signed ones' image");
    }
  }
  // A mirroring actor transform (scale x by -1) equals the mirror image made in the data (x
  // negated, winding reversed, tangents computed anew) where VTK derives the normal from the
  // position's derivatives (Flat), for both frame sources. Same arithmetic up to float rounding:
  // 2 levels on 99.9% of the pixels. A frame built around the inward normal turns every rivet's
  // light and shadow.
  {
    auto mirrored = vtkSmartPointer<vtkPolyData>::New();
    mirrored->DeepCopy(nmtest::MakeQuad(2));
    vtkPoints* points = mirrored->GetPoints();
    for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
    {
      double x[3];
      points->GetPoint(p, x);
      points->SetPoint(p, -x[0], x[1], x[2]);
    }
    mirrored->BuildCells();
    for (vtkIdType c = 0; c < mirrored->GetNumberOfCells(); ++c)
    {
      mirrored->ReverseCell(c);
    }
    auto premirrored = nmtest::WithTangents(mirrored);
    for (int frame : { Mapper::POINT_TANGENTS, Mapper::SCREEN_DERIVATIVES })
    {
      std::vector<unsigned char> images[2];
      for (int k = 0; k < 2; ++k)
      {
        nmtest::FlatActor a;
        a.Mesh = k == 0 ? quad.Get() : premirrored.Get();
        a.NormalTexture = openGL;
        a.FrameSource = frame;
        a.Interpolation = VTK_FLAT;
        a.Scale[0] = k == 0 ? -1.0 : 1.0;
        images[k] = nmtest::RenderFlat(setup, { a });
      }
      const auto d = Between(images[0], images[1], 2);
      const std::string what = std::string("mirroring actor transform, Flat, ") +
        (frame == Mapper::POINT_TANGENTS ? "point tangents" : "derivatives");
      Report(what.c_str(), d, 2);
      check(d.WithinFraction >= 0.999, what + ": the same as the mirrored data");
    }
  }
  // Without tangents the automatic source is the derivative frame.
  {
    int noTangentsApplied = -1;
    nmtest::FlatActor a;
    auto bare = nmtest::MakeQuad(2);
    a.Mesh = bare;
    a.NormalTexture = openGL;
    a.AppliedFrame = &noTangentsApplied;
    nmtest::RenderFlat(setup, { a });
    check(noTangentsApplied == Mapper::APPLIED_DERIVATIVES, "no tangents: derivative frame");
  }
  // A strength-0.5 image lies between the unmapped one and the strength-1 one: it differs from
  // both, and from the unmapped one by less than strength 1 does.
  const auto checkBetween = [&](const std::vector<unsigned char>& plain,
                              const std::vector<unsigned char>& half,
                              const std::vector<unsigned char>& full,
                              const std::string& what)
  {
    const auto toFull = Between(full, half, 0), toPlain = Between(plain, half, 0);
    std::cout << what << " at strength 0.5: max difference to strength 1: " << toFull.MaxChannel
              << ", to strength 0: " << toPlain.MaxChannel << std::endl;
    check(toFull.MaxChannel > 0 && toPlain.MaxChannel > 0 &&
        toPlain.MaxChannel < Between(plain, full, 0).MaxChannel,
      what + ": strength 0.5 perturbs less than strength 1");
  };
  // Strength 0 is exactly the unmapped image, ours and VTK's; strength 0.5 lies in between.
  {
    std::string zeroShaders;
    const auto zero =
      render(openGL, Mapper::TANGENT_SPACE_OPENGL, Mapper::AUTOMATIC, 0.0, false, &zeroShaders);
    std::string plainShaders;
    const auto plain =
      render(nullptr, Mapper::TANGENT_SPACE_OPENGL, Mapper::AUTOMATIC, 1.0, false, &plainShaders);
    const auto stockPlain = render(nullptr, 0, 0, 1.0, true);
    check(Between(zero, plain, 0).WithinFraction == 1.0 && Between(zero, plain, 0).MaxChannel == 0,
      "strength 0 renders exactly the image without a normal map");
    check(Between(plain, stockPlain, 0).MaxChannel == 0,
      "without a normal map ours renders exactly what VTK's mapper renders");
    check(zeroShaders.find("nmNormal") == std::string::npos &&
        plainShaders.find("nm") == std::string::npos,
      "no normal-map code at strength 0 or without a normal texture");
    checkBetween(plain,
      render(openGL, Mapper::TANGENT_SPACE_OPENGL, Mapper::AUTOMATIC, 0.5),
      reference,
      "tangent space");
  }
  // Object space at strength 0.5: the normal blended halfway from the surface's to the map's,
  // so the image lies between the unmapped one and strength 1.
  {
    checkBetween(render(nullptr, Mapper::OBJECT_SPACE, Mapper::AUTOMATIC),
      render(openGL, Mapper::OBJECT_SPACE, Mapper::AUTOMATIC, 0.5),
      render(openGL, Mapper::OBJECT_SPACE, Mapper::AUTOMATIC, 1.0),
      "object space");
  }
  // Point tangents off the tangent plane and off unit length: the shader makes them
  // perpendicular to the normal per fragment, so they render as their projections, which are
  // the reference's tangents (1 level: float rounding of the projection).
  {
    auto tilted = vtkSmartPointer<vtkPolyData>::New();
    tilted->DeepCopy(quad);
    vtkDataArray* tangents = tilted->GetPointData()->GetTangents();
    vtkDataArray* normals = tilted->GetPointData()->GetNormals();
    for (vtkIdType p = 0; p < tangents->GetNumberOfTuples(); ++p)
    {
      double t[3], n[3];
      tangents->GetTuple(p, t);
      normals->GetTuple(p, n);
      tangents->SetTuple3(p, 2 * t[0] + n[0], 2 * t[1] + n[1], 2 * t[2] + n[2]);
    }
    nmtest::FlatActor a;
    a.Mesh = tilted;
    a.NormalTexture = openGL;
    const auto d = Between(reference, nmtest::RenderFlat(setup, { a }), 1);
    Report("tangents off the tangent plane vs unit perpendicular tangents", d, 1);
    check(d.WithinFraction == 1.0, "tangents off the tangent plane render as their projections");
  }
  // The shader follows changes of the texture between renders of the same actor: its sRGB flag
  // (then decoded back to the stored values) and its number of components (a two-channel image
  // under an RGB encoding is read as a two-channel map, "ra" of VTK's luminance-alpha upload).
  // Both describe the same surface as before the change, within the bounds of the sRGB test in
  // TestNormalMapBadInput (3 levels) and of the two-channel comparison above (2 levels); a
  // shader left as it was reads the new texture wrongly.
  {
    const auto beforeAndAfter = [&](vtkTexture* texture, const std::function<void()>& change)
    {
      nmtest::FlatActor a;
      a.Mesh = quad;
      a.NormalTexture = texture;
      auto window = nmtest::MakeFlatScene(setup, { a });
      window->Render();
      std::vector<std::vector<unsigned char>> images{ nmtest::ReadPixels(window) };
      change();
      window->Render();
      images.push_back(nmtest::ReadPixels(window));
      return images;
    };
    // vtkProperty refuses a texture marked sRGB, but the flag can be turned on afterwards.
    auto texture = image(nmtest::Storage::OpenGL);
    const auto srgb = beforeAndAfter(texture, [&]() { texture->UseSRGBColorSpaceOn(); });
    const auto toSRGB = Between(srgb[0], srgb[1], 3);
    Report("texture marked sRGB after a render vs before", toSRGB, 3);
    check(toSRGB.WithinFraction == 1.0, "the shader follows the texture's sRGB flag");

    auto rgb = image(nmtest::Storage::OpenGL);
    auto twoChannel = nmtest::MakeNormalMapImage(pattern, 128, nmtest::Storage::TwoChannel);
    const auto channels = beforeAndAfter(rgb, [&]() { rgb->SetInputData(twoChannel); });
    const auto toTwoChannel = Between(channels[0], channels[1], 2);
    Report("RGB image replaced by a two-channel one after a render vs before", toTwoChannel, 2);
    check(toTwoChannel.WithinFraction == 1.0, "the shader follows the texture's components");
  }
  // Point scalars colored through the color map and interpolated before mapping (ParaView's
  // default): VTK's texture coordinates are then the color map's, so the mappers sample the
  // normal texture at their own copy of the dataset's. The image is that of the scalars mapped
  // at the points, for both mappers (the same arithmetic: 0 levels), also with edges shown
  // (VTK then draws through a geometry shader, which passes the coordinates on), and with the
  // setting turned on after a render. Sampled at the color map's coordinates (constant here),
  // the map would show no rivets.
  {
    auto colored = vtkSmartPointer<vtkPolyData>::New();
    colored->ShallowCopy(quad);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("Value");
    scalars->SetNumberOfTuples(colored->GetNumberOfPoints());
    scalars->Fill(0.5);
    colored->GetPointData()->SetScalars(scalars);
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetBlock(0, colored);
    auto coloredActor = [&](bool composite, bool interpolate, bool edges = false)
    {
      nmtest::FlatActor a;
      a.Mesh = colored;
      a.Blocks = composite ? blocks.Get() : nullptr;
      a.NormalTexture = openGL;
      a.InterpolateScalars = interpolate;
      a.EdgeVisibility = edges;
      return a;
    };
    // The mapper of a flat scene's only actor.
    const auto mapperOf = [](vtkRenderWindow* window) {
      return window->GetRenderers()->GetFirstRenderer()->GetActors()->GetLastActor()->GetMapper();
    };
    for (bool composite : { false, true })
    {
      const std::string mapper = composite ? "composite mapper" : "single mapper";
      std::vector<unsigned char> interpolated; // the last image: without edges
      for (bool edges : { true, false })
      {
        const std::string what = mapper + (edges ? ", edges shown" : "");
        const auto atPoints = nmtest::RenderFlat(setup, { coloredActor(composite, false, edges) });
        interpolated = nmtest::RenderFlat(setup, { coloredActor(composite, true, edges) });
        const auto d = Between(interpolated, atPoints, 0);
        Report(
          ("scalars interpolated before mapping vs mapped at the points, " + what).c_str(), d, 0);
        check(
          d.WithinFraction == 1.0, "scalars interpolated before mapping, " + what + ": the map");
      }

      auto window = nmtest::MakeFlatScene(setup, { coloredActor(composite, false) });
      window->Render();
      mapperOf(window)->InterpolateScalarsBeforeMappingOn();
      window->Render();
      const auto turnedOn = Between(nmtest::ReadPixels(window), interpolated, 0);
      Report(("interpolation turned on after a render vs from the start, " + mapper).c_str(),
        turnedOn,
        0);
      check(turnedOn.WithinFraction == 1.0,
        "scalars interpolated before mapping from a later render, " + mapper + ": the map");
    }
    // A normal texture that reads texture coordinates of its own (mapped to an attribute by
    // name) is sampled there as VTK samples it, whatever the color map does.
    {
      const auto atPoints = nmtest::RenderFlat(setup, { coloredActor(false, false) });
      auto window = nmtest::MakeFlatScene(setup, { coloredActor(false, true) });
      vtkOpenGLPolyDataMapper::SafeDownCast(mapperOf(window))
        ->MapDataArrayToMultiTextureAttribute(
          "normalTex", "TCoords", vtkDataObject::FIELD_ASSOCIATION_POINTS);
      window->Render();
      const auto d = Between(nmtest::ReadPixels(window), atPoints, 0);
      Report("scalars interpolated before mapping, the map's own mapped texture coordinates", d, 0);
      check(d.WithinFraction == 1.0,
        "scalars interpolated before mapping, the map's own mapped texture coordinates: the map");
    }
    // With a texture transform (v flipped) VTK also transforms the color map's coordinates (the
    // colors differ), and the mappers transform their own copy as VTK would the texture
    // coordinates: the two frame sources agree as in the transform test above.
    const double flip[16] = { 1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1 };
    std::vector<unsigned char> images[2];
    for (int k = 0; k < 2; ++k)
    {
      nmtest::FlatActor a = coloredActor(false, true);
      a.TextureTransform = flip;
      a.FrameSource = k == 0 ? Mapper::POINT_TANGENTS : Mapper::SCREEN_DERIVATIVES;
      images[k] = nmtest::RenderFlat(setup, { a });
    }
    const auto d = Between(images[0], images[1], 2);
    Report("scalars interpolated before mapping, v flipped: point tangents vs derivatives", d, 2);
    check(d.WithinFraction >= 0.999,
      "scalars interpolated before mapping, v flipped: the frame sources agree");
  }
  // Every lighting model shows the map: with it the image differs from without it, by more
  // than rounding (Flat: the face normal from derivatives is perturbed; Gouraud is lit per
  // fragment in VTK's OpenGL2 backend like Phong; PBR).
  for (int interpolation : { VTK_FLAT, VTK_GOURAUD, VTK_PBR })
  {
    nmtest::FlatActor withMap, withoutMap;
    withMap.Mesh = withoutMap.Mesh = quad;
    withMap.NormalTexture = openGL;
    withMap.Interpolation = withoutMap.Interpolation = interpolation;
    int appliedFrame = -1;
    withMap.AppliedFrame = &appliedFrame;
    const auto a = nmtest::RenderFlat(setup, { withMap });
    const auto b = nmtest::RenderFlat(setup, { withoutMap });
    const auto d = Between(a, b, 2);
    std::cout << "interpolation " << interpolation << ": " << 100.0 * (1.0 - d.WithinFraction)
              << "% of pixels changed by the map, max " << d.MaxChannel << std::endl;
    check(appliedFrame == Mapper::APPLIED_POINT_TANGENTS && d.MaxChannel > 20 &&
        d.WithinFraction < 0.95,
      std::string("the map shows with interpolation ") + std::to_string(interpolation));
  }
  return check.Result();
}
