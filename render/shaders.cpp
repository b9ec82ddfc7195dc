#include "render/shaders.h"

#include <string>
#include <utility>

#include <epoxy/gl.h>

#include "haptics/core/error.h"

namespace voxhap::render {
namespace {

/// Shared by the fragment shaders: linear RGB to sRGB display values.
constexpr const char* kSrgbFunction = R"(
vec3 encodeSrgb(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
)";

constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 positionScene;
layout(location = 1) in vec3 normalScene;
layout(location = 2) in vec4 vertexColour;
uniform mat4 worldToClip;
uniform mat4 modelToWorld;
uniform mat3 normalToWorld;
uniform vec4 baseColour;
uniform bool useVertexColour;
out vec3 normalWorld;
out vec4 colourLinear;
void main() {
  gl_Position = worldToClip * (modelToWorld * vec4(positionScene, 1.0));
  normalWorld = normalToWorld * normalScene;
  colourLinear = useVertexColour ? vec4(vertexColour.rgb, baseColour.a) : baseColour;
}
)";

constexpr const char* kLitFragment = R"(
in vec3 normalWorld;
in vec4 colourLinear;
uniform vec3 keyLightWorld;
uniform vec3 fillLightWorld;
out vec4 fragColour;
void main() {
  vec3 n = normalize(normalWorld);
  if (!gl_FrontFacing) n = -n;
  float light = 0.22 + 0.68 * max(dot(n, keyLightWorld), 0.0) + 0.25 * max(dot(n, fillLightWorld), 0.0);
  fragColour = vec4(encodeSrgb(colourLinear.rgb * light), colourLinear.a);
}
)";

constexpr const char* kFlatVertex = R"(#version 330 core
layout(location = 0) in vec3 positionLocal;
layout(location = 3) in vec3 instanceOffsetWorld;
uniform mat4 worldToClip;
uniform mat4 modelToWorld;
uniform float instanceScale;
void main() {
  vec4 world = modelToWorld * vec4(positionLocal * instanceScale, 1.0) + vec4(instanceOffsetWorld, 0.0);
  gl_Position = worldToClip * world;
}
)";

constexpr const char* kFlatFragment = R"(
uniform vec4 colour;
out vec4 fragColour;
void main() { fragColour = vec4(encodeSrgb(colour.rgb), colour.a); }
)";

constexpr const char* kCopyVertex = R"(#version 330 core
void main() {
  // one triangle covering the viewport: (-1,-1), (3,-1), (-1,3)
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

constexpr const char* kCopyFragment = R"(
uniform sampler2D colourTexture;
uniform sampler2D depthTexture;
out vec4 fragColour;
void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  fragColour = texelFetch(colourTexture, texel, 0);
  gl_FragDepth = texelFetch(depthTexture, texel, 0).r;
}
)";

std::string fragmentSource(const char* body) {
  return std::string("#version 330 core\n") + kSrgbFunction + body;
}

GLuint compileStage(const char* programName, GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  glDeleteShader(shader);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  throw Error(std::string("shader ") + programName + ": the " +
              (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") + " stage does not compile: " + log);
}

}  // namespace

ShaderProgram::ShaderProgram(const char* name, const char* vertexSource, const char* fragmentSource)
    : name_(name) {
  const GLuint vertex = compileStage(name, GL_VERTEX_SHADER, vertexSource);
  GLuint fragment = 0;
  try {
    fragment = compileStage(name, GL_FRAGMENT_SHADER, fragmentSource);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vertex);
  glAttachShader(id_, fragment);
  glLinkProgram(id_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return;
  GLint length = 0;
  glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(id_, length, nullptr, log.data());
  glDeleteProgram(id_);
  id_ = 0;
  throw Error(std::string("shader ") + name + ": the program does not link: " + log.c_str());
}

ShaderProgram::~ShaderProgram() {
  if (id_ != 0) glDeleteProgram(id_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : name_(other.name_), id_(std::exchange(other.id_, 0)) {}

void ShaderProgram::use() const {
  glUseProgram(id_);
}

int ShaderProgram::uniform(const char* name) const {
  const GLint location = glGetUniformLocation(id_, name);
  if (location < 0) throw Error(std::string("shader ") + name_ + ": no uniform " + name);
  return location;
}

LitShader::LitShader()
    : program("lit", kLitVertex, fragmentSource(kLitFragment).c_str()),
      worldToClip(program.uniform("worldToClip")),
      modelToWorld(program.uniform("modelToWorld")),
      normalToWorld(program.uniform("normalToWorld")),
      baseColour(program.uniform("baseColour")),
      useVertexColour(program.uniform("useVertexColour")),
      keyLightWorld(program.uniform("keyLightWorld")),
      fillLightWorld(program.uniform("fillLightWorld")) {}

FlatShader::FlatShader()
    : program("flat", kFlatVertex, fragmentSource(kFlatFragment).c_str()),
      worldToClip(program.uniform("worldToClip")),
      modelToWorld(program.uniform("modelToWorld")),
      instanceScale(program.uniform("instanceScale")),
      colour(program.uniform("colour")) {}

CacheCopyShader::CacheCopyShader()
    : program("cache copy", kCopyVertex, fragmentSource(kCopyFragment).c_str()),
      colourTexture(program.uniform("colourTexture")),
      depthTexture(program.uniform("depthTexture")) {}

}  // namespace voxhap::render
