#pragma once
/// The renderer's GLSL 3.30 programs: a lit one for scene parts, a flat one for overlays,
/// and the copy of the static cache into the default framebuffer.
///
/// Colours in uniforms and vertex streams are linear RGB (as a Part's baseColor); the
/// fragment shaders encode sRGB on output, so the default framebuffer holds display values.
/// Every constructor needs a current GL context and throws voxhap::Error with the
/// driver's log when a stage does not compile or the program does not link.

#include <cstdint>

namespace voxhap::render {

/// A linked GL program. Move-only; deletes the program with it.
class ShaderProgram {
public:
  /// `name` appears in errors: "shader lit: the fragment stage does not compile: 0:12(3): …".
  ShaderProgram(const char* name, const char* vertexSource, const char* fragmentSource);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&&) = delete;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  std::uint32_t id() const { return id_; }
  void use() const;
  /// Location of a uniform; throws voxhap::Error naming it when the program has none.
  int uniform(const char* name) const;

private:
  const char* name_;
  std::uint32_t id_ = 0;
};

/// Vertex attribute locations shared by every mesh and program.
enum AttributeLocation : std::uint32_t {
  kPositionAttribute = 0,        ///< vec3, object's scene-placement frame (m)
  kNormalAttribute = 1,          ///< vec3, same frame, unit
  kColourAttribute = 2,          ///< RGBA8 normalised, linear (proximity colours)
  kInstanceOffsetAttribute = 3,  ///< vec3 per instance, world frame (m)
};

/// Two-light diffuse shading with world-space normals; the part's base colour or the
/// per-vertex colour stream. Back faces are lit as if facing the eye (open meshes).
struct LitShader {
  LitShader();
  ShaderProgram program;
  int worldToClip;      ///< mat4
  int modelToWorld;     ///< mat4: the object's pose
  int normalToWorld;    ///< mat3: the pose's rotation
  int baseColour;       ///< vec4, linear
  int useVertexColour;  ///< bool: take the colour stream instead of baseColour
  int keyLightWorld;    ///< vec3, unit, towards the light
  int fillLightWorld;   ///< vec3, unit, towards the light
};

/// One flat colour, optionally blended; positions scaled by `instanceScale` and offset by
/// the per-instance attribute (zero when the attribute array is off).
struct FlatShader {
  FlatShader();
  ShaderProgram program;
  int worldToClip;    ///< mat4
  int modelToWorld;   ///< mat4
  int instanceScale;  ///< float
  int colour;         ///< vec4, linear RGB and alpha
};

/// A full-screen triangle that writes a colour texture's texels and a depth texture's
/// depths (gl_FragDepth) pixel for pixel: the static cache's copy.
struct CacheCopyShader {
  CacheCopyShader();
  ShaderProgram program;
  int colourTexture;  ///< sampler2D, unit 0
  int depthTexture;   ///< sampler2D, unit 1
};

}  // namespace voxhap::render
