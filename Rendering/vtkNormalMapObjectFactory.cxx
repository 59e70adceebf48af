// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMapObjectFactory.h"

#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactoryCollection.h"
#include "vtkVersion.h"

#include <string>

vtkStandardNewMacro(vtkNormalMapObjectFactory);

namespace
{
vtkObject* CreateNormalMapPolyDataMapper()
{
  return vtkNormalMapPolyDataMapper::New();
}

vtkObject* CreateNormalMapCompositePolyDataMapper()
{
  return vtkNormalMapCompositePolyDataMapper::New();
}

/// VTK's composite polydata mapper: vtkNormalMapCompositePolyDataMapper's superclass.
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
constexpr const char* CompositeMapper = "vtkCompositePolyDataMapper";
#else
constexpr const char* CompositeMapper = "vtkCompositePolyDataMapper2";
#endif

/// The classes overridden, each with its replacement.
const char* const Overrides[][2] = {
  { "vtkPolyDataMapper", "vtkNormalMapPolyDataMapper" },
  { CompositeMapper, "vtkNormalMapCompositePolyDataMapper" },
};

/// The registered factory, or nullptr.
vtkNormalMapObjectFactory* Registered()
{
  vtkObjectFactoryCollection* factories = vtkObjectFactory::GetRegisteredFactories();
  vtkCollectionSimpleIterator it;
  factories->InitTraversal(it);
  while (vtkObjectFactory* factory = factories->GetNextObjectFactory(it))
  {
    if (auto* ours = vtkNormalMapObjectFactory::SafeDownCast(factory))
    {
      return ours;
    }
  }
  return nullptr;
}
}

//------------------------------------------------------------------------------
vtkNormalMapObjectFactory::vtkNormalMapObjectFactory()
{
  this->RegisterOverride("vtkPolyDataMapper",
    "vtkNormalMapPolyDataMapper",
    "Normal-mapping polydata mapper",
    1,
    CreateNormalMapPolyDataMapper);
  this->RegisterOverride(CompositeMapper,
    "vtkNormalMapCompositePolyDataMapper",
    "Normal-mapping composite polydata mapper",
    1,
    CreateNormalMapCompositePolyDataMapper);
}

//------------------------------------------------------------------------------
const char* vtkNormalMapObjectFactory::GetVTKSourceVersion()
{
  return VTK_SOURCE_VERSION;
}

//------------------------------------------------------------------------------
const char* vtkNormalMapObjectFactory::GetDescription()
{
  static const std::string description =
    std::string("VTK::NormalMapping: vtkNormalMapPolyDataMapper for vtkPolyDataMapper, "
                "vtkNormalMapCompositePolyDataMapper for ") +
    CompositeMapper;
  return description.c_str();
}

//------------------------------------------------------------------------------
void vtkNormalMapObjectFactory::Install()
{
  if (!Registered())
  {
    vtkNew<vtkNormalMapObjectFactory> factory;
    vtkObjectFactory::RegisterFactory(factory);
  }
  // The first enabled override wins; VTK's OpenGL module registered its own earlier.
  for (const auto& pair : Overrides)
  {
    vtkObjectFactory::SetAllEnableFlags(false, pair[0]);
    vtkObjectFactory::SetAllEnableFlags(true, pair[0], pair[1]);
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapObjectFactory::Uninstall()
{
  if (vtkNormalMapObjectFactory* factory = Registered())
  {
    vtkObjectFactory::UnRegisterFactory(factory);
  }
  for (const auto& pair : Overrides)
  {
    vtkObjectFactory::SetAllEnableFlags(true, pair[0]);
  }
}

//------------------------------------------------------------------------------
bool vtkNormalMapObjectFactory::IsInstalled()
{
  return Registered() != nullptr;
}
