// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMapObjectFactory.h"

#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactoryCollection.h"
#include "vtkVersion.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

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

/// An override of another factory that Install() disabled, for Uninstall() to enable again.
struct DisabledOverride
{
  vtkWeakPointer<vtkObjectFactory> Factory;
  std::string ClassName;
  std::string SubclassName;
};

std::vector<DisabledOverride>& DisabledOverrides()
{
  static std::vector<DisabledOverride> disabled;
  return disabled;
}

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
  // The first enabled override wins; VTK's OpenGL module registered its own earlier. Every
  // other factory's enabled override of the classes is disabled, and remembered.
  vtkObjectFactoryCollection* factories = vtkObjectFactory::GetRegisteredFactories();
  vtkCollectionSimpleIterator it;
  factories->InitTraversal(it);
  while (vtkObjectFactory* factory = factories->GetNextObjectFactory(it))
  {
    if (vtkNormalMapObjectFactory::SafeDownCast(factory))
    {
      continue;
    }
    for (int i = 0; i < factory->GetNumberOfOverrides(); ++i)
    {
      const std::string className = factory->GetClassOverrideName(i);
      const bool overridden = std::any_of(std::begin(Overrides),
        std::end(Overrides),
        [&](const auto& pair) { return className == pair[0]; });
      if (overridden && factory->GetEnableFlag(i))
      {
        const std::string subclassName = factory->GetClassOverrideWithName(i);
        factory->SetEnableFlag(false, className.c_str(), subclassName.c_str());
        DisabledOverrides().push_back({ factory, className, subclassName });
      }
    }
  }
  for (const auto& pair : Overrides)
  {
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
  for (const DisabledOverride& disabled : DisabledOverrides())
  {
    if (disabled.Factory)
    {
      disabled.Factory->SetEnableFlag(
        true, disabled.ClassName.c_str(), disabled.SubclassName.c_str());
    }
  }
  DisabledOverrides().clear();
}

//------------------------------------------------------------------------------
bool vtkNormalMapObjectFactory::IsInstalled()
{
  return Registered() != nullptr;
}
