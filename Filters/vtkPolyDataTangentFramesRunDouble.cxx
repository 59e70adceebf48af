// vtkPolyDataTangentFrames' execution with double output (see vtkPolyDataTangentFramesInternals.h).
#include "vtkPolyDataTangentFramesInternals.h"

VTK_TANGENT_FRAMES_RUN_INSTANCE(double);
