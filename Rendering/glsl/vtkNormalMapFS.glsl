// SPDX-License-Identifier: BSD-3-Clause
// Fragment-shader pieces of vtkNormalMapPolyDataMapper. Each block between "//NM::Begin <name>"
// and "//NM::End" is inserted at one of VTK's shader tags when the scene needs it.
//
// The perturbed normal is built in model coordinates (MC) and then transformed like every
// normal, by the inverse transpose of the model-view matrix (nmNormalMatrix). A normal-mapped
// surface is a stand-in for displaced geometry, whose normals transform that way, so this is
// right under non-uniform and mirroring transforms too. The frame (tangent, bitangent, normal)
// is re-orthogonalized per fragment in model coordinates.

//NM::Begin Dec
// Inverse transpose of the model-view matrix's linear part, and its inverse.
uniform mat3 nmNormalMatrix;
uniform mat3 nmNormalMatrixInverse;
// vtkProperty::NormalScale: a tangent-space map's x and y scale (glTF's normalTexture.scale);
// for an object-space map, the blend from the surface normal (0) to the map's (1).
uniform float nmNormalScale;
// +1 when the map's green channel points along +bitangent (OpenGL), -1 when it points along
// -bitangent (DirectX).
uniform float nmGreenSign;

// The frame (T, B, N) of the unit normal n: T the unit part of `direction` perpendicular to n
// (Gram-Schmidt), B = sign(s) * cross(n, T) (s < 0: -1, else +1). Where that part's squared
// length is not above minLen2 (or not a number), zero T and B columns: no perturbation.
mat3 nmOrthoFrame(vec3 direction, float s, vec3 n, float minLen2)
{
  vec3 t = direction - dot(direction, n) * n;
  float len2 = dot(t, t);
  if (!(len2 > minLen2))
  {
    return mat3(vec3(0.0), vec3(0.0), n);
  }
  t *= inversesqrt(len2);
  return mat3(t, (s < 0.0 ? -1.0 : 1.0) * cross(n, t), n);
}
//NM::End

//NM::Begin TexelLinear
vec4 nmStoredTexel(vec4 texel) { return texel; }
//NM::End

//NM::Begin TexelSRGB
// The texture was uploaded as sRGB, so sampling decoded it; encode again to get the stored
// values back (the map is data, not colour).
vec4 nmStoredTexel(vec4 texel)
{
  vec3 c = clamp(texel.rgb, 0.0, 1.0);
  vec3 low = c * 12.92;
  vec3 high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return vec4(mix(high, low, vec3(lessThanEqual(c, vec3(0.0031308)))), texel.a);
}
//NM::End

//NM::Begin FlippedAttribute
// Whether VTK flipped the normal: it flips point and cell normals on back faces.
bool nmFlipped() { return gl_FrontFacing == false; }
//NM::End

//NM::Begin FlippedDerived
// Whether VTK's normal is the back of the surface: the normal it derives from the position's
// derivatives faces the camera, which is the back on back faces, and with a mirroring model-view
// transform (nmMirrored, det < 0) on the faces GL calls front faces.
uniform int nmMirrored;
bool nmFlipped() { return (gl_FrontFacing == false) != (nmMirrored != 0); }
//NM::End

//NM::Begin DecodeRGB
// Tangent-space normal from an RGB texel, strength applied (left unnormalized: the final
// normalize makes its length irrelevant).
vec3 nmDecode(vec4 texel)
{
  vec3 n = texel.rgb * 2.0 - 1.0;
  return vec3(n.x * nmNormalScale, n.y * nmGreenSign * nmNormalScale, n.z);
}
//NM::End

//NM::Begin DecodeTwoChannel
// Tangent-space normal from two channels; z = sqrt(1 - x^2 - y^2). @XY@ is "rg", or "ra" for a
// 2-component image, which VTK uploads as luminance-alpha (x, x, x, y).
vec3 nmDecode(vec4 texel)
{
  vec2 xy = texel.@XY@ * 2.0 - 1.0;
  float z = sqrt(max(0.0, 1.0 - dot(xy, xy)));
  return vec3(xy.x * nmNormalScale, xy.y * nmGreenSign * nmNormalScale, z);
}
//NM::End

//NM::Begin TCoordDec
// The dataset's texture coordinates, where VTK's tcoord holds the color map's.
in vec2 nmTCoordVCVSOutput;
//NM::End

//NM::Begin TangentDec
// The interpolated point tangent; w its handedness sign, 0 for tangents without one.
in vec4 nmTangentMCVSOutput;
// The texture coordinates' transform (vtkProp::GeneralTextureTransform), M on (u, v), as seen
// from the point tangents: (x, y) of the direction of dP/du' in (dP/du, dP/dv) for the
// transformed u' (the first column of M^-1, scaled by |det M|), and the sign of det M, which
// turns the handedness. Without a transform (1, 0, 1).
uniform vec3 nmTextureFrame;
//NM::End

//NM::Begin HandednessStored
// The handedness the point tangents carry.
float nmHandedness(vec3 normalMC) { return nmTangentMCVSOutput.w; }
//NM::End

//NM::Begin HandednessDerived
// Tangents without a sign (w = 0) take the orientation of the texture coordinates on the
// triangle under the fragment, which is the sign a signed tangent carries there; for the
// untransformed coordinates, so turned by the transform's sign (nmTextureFrame.z).
float nmHandedness(vec3 normalMC)
{
  float w = nmTangentMCVSOutput.w;
  return w != 0.0 ? w : nmUVOrientation(normalMC) * nmTextureFrame.z;
}
//NM::End

//NM::Begin TangentFrame
// Frame from the interpolated point tangent and its handedness (nmOrthoFrame), for the
// transformed texture coordinates. A tangent parallel to the normal leaves the unperturbed
// normal.
mat3 nmTangentFrameMC(vec3 normalMC)
{
  vec3 t = nmTangentMCVSOutput.xyz;
  float w = nmHandedness(normalMC);
  t = nmTextureFrame.x * t + nmTextureFrame.y * (w * cross(normalMC, t));
  return nmOrthoFrame(t, w * nmTextureFrame.z, normalMC, 1e-12 * dot(t, t));
}
//NM::End

//NM::Begin DerivativeDec
// Screen-space derivatives of the view-coordinate position and the texture coordinates, taken
// in uniform control flow.
vec3 nmDPositionDx;
vec3 nmDPositionDy;
vec2 nmDTCoordDx;
vec2 nmDTCoordDy;

// The triangle under the fragment, from the derivatives: its position's derivatives in model
// coordinates (the model-view inverse is the transpose of nmNormalMatrix), and det * dP/du and
// det * dP/dv solved from them, det the determinant of the texture coordinates' derivatives.
void nmDerivativeAxesMC(out vec3 dpdx, out vec3 dpdy, out vec3 dpdu, out vec3 dpdv, out float det)
{
  dpdx = nmDPositionDx * nmNormalMatrix;
  dpdy = nmDPositionDy * nmNormalMatrix;
  det = nmDTCoordDx.x * nmDTCoordDy.y - nmDTCoordDy.x * nmDTCoordDx.y;
  dpdu = dpdx * nmDTCoordDy.y - dpdy * nmDTCoordDx.y;
  dpdv = dpdy * nmDTCoordDx.x - dpdx * nmDTCoordDy.x;
}

// The orientation of the texture coordinates on that triangle against the normal: -1 where
// they are mirrored, else +1 (also where they are degenerate).
float nmUVOrientation(vec3 normalMC)
{
  vec3 dpdx, dpdy, dpdu, dpdv;
  float det;
  nmDerivativeAxesMC(dpdx, dpdy, dpdu, dpdv, det);
  return dot(cross(dpdu, dpdv), normalMC) < 0.0 ? -1.0 : 1.0;
}

// Frame of that triangle: the tangent is dP/du made perpendicular to the normal, the sign is
// the orientation of the texture coordinates (nmUVOrientation). Same conventions as the point
// tangents, so both sources agree on flat triangles. Degenerate texture coordinates give zero T
// and B columns: no perturbation.
mat3 nmDerivativeFrameMC(vec3 normalMC)
{
  vec3 dpdx, dpdy, dpdu, dpdv;
  float det;
  nmDerivativeAxesMC(dpdx, dpdy, dpdu, dpdv, det);
  float scale2 = (dot(dpdx, dpdx) + dot(dpdy, dpdy)) *
    (dot(nmDTCoordDx, nmDTCoordDx) + dot(nmDTCoordDy, nmDTCoordDy));
  return nmOrthoFrame(det < 0.0 ? -dpdu : dpdu,
    dot(cross(dpdu, dpdv), normalMC),
    normalMC,
    1e-10 * scale2);
}
//NM::End

//NM::Begin FrameFromTangents
mat3 nmFrameMC(vec3 normalMC) { return nmTangentFrameMC(normalMC); }
//NM::End

//NM::Begin FrameFromDerivatives
mat3 nmFrameMC(vec3 normalMC) { return nmDerivativeFrameMC(normalMC); }
//NM::End

//NM::Begin FramePerDataset
// Composite data drawn by one shader: the datasets with point tangents use them, the others
// (whose tangent attribute is zero) use derivatives; the mapper sets this before each draw.
uniform int nmDatasetHasTangents;
mat3 nmFrameMC(vec3 normalMC)
{
  return nmDatasetHasTangents != 0 ? nmTangentFrameMC(normalMC) : nmDerivativeFrameMC(normalMC);
}
//NM::End

//NM::Begin DerivativeUniformFlow
  nmDPositionDx = dFdx(vertexVC.xyz);
  nmDPositionDy = dFdy(vertexVC.xyz);
  nmDTCoordDx = dFdx(@TCOORD@VCVSOutput);
  nmDTCoordDy = dFdy(@TCOORD@VCVSOutput);
//NM::End

//NM::Begin ImplTangentSpace
  {
    // Normal mapping (vtkNormalMapPolyDataMapper). Where VTK's normal is the surface's back
    // (nmFlipped), turn it to the front, perturb the front side, then flip the result: the back
    // of a bumpy sheet sees the mirror of the front's normal.
    vec3 nmFrontVC = nmFlipped() ? -normalVCVSOutput : normalVCVSOutput;
    vec3 nmNormalMC = normalize(nmNormalMatrixInverse * nmFrontVC);
    vec3 nmMapped = nmDecode(nmStoredTexel(texture(normalTex, @TCOORD@VCVSOutput)));
    vec3 nmPerturbedVC = normalize(nmNormalMatrix * (nmFrameMC(nmNormalMC) * nmMapped));
    normalVCVSOutput = nmFlipped() ? -nmPerturbedVC : nmPerturbedVC;
  }
//NM::End

//NM::Begin ImplObjectSpace
  {
    // Normal mapping (vtkNormalMapPolyDataMapper), object-space map: the texel is the normal
    // in model coordinates; NormalScale blends from the surface normal (0) to the map's (1).
    vec3 nmFrontVC = nmFlipped() ? -normalVCVSOutput : normalVCVSOutput;
    vec3 nmNormalMC = normalize(nmNormalMatrixInverse * nmFrontVC);
    vec3 nmMapMC = nmStoredTexel(texture(normalTex, @TCOORD@VCVSOutput)).rgb * 2.0 - 1.0;
    vec3 nmBlendMC = mix(nmNormalMC, nmMapMC, nmNormalScale);
    vec3 nmPerturbedVC = normalize(nmNormalMatrix * nmBlendMC);
    normalVCVSOutput = nmFlipped() ? -nmPerturbedVC : nmPerturbedVC;
  }
//NM::End
