#include "haptics/scene/gltf_accessors.h"

#include <cmath>
#include <cstring>

#include "haptics/core/error.h"

namespace voxhap {

std::vector<glm::vec3> AccessorReader::positions(int accessorIndex, const std::string& where) const {
  const View view = check(accessorIndex, where + ": POSITION");
  if (view.accessor->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
      view.accessor->type != TINYGLTF_TYPE_VEC3) {
    throw Error(view.where + " must be float VEC3");
  }
  std::vector<glm::vec3> out(view.accessor->count);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::memcpy(&out[i], view.data + i * view.stride, sizeof(glm::vec3));
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(out[i][k])) {
        throw Error(view.where + ": position " + std::to_string(i) + " is " +
                    (std::isnan(out[i][k]) ? "NaN" : "infinite"));
      }
    }
  }
  return out;
}

std::vector<std::uint32_t> AccessorReader::indices(int accessorIndex, std::size_t vertexCount,
                                                   const std::string& where) const {
  const View view = check(accessorIndex, where + ": indices");
  const int type = view.accessor->componentType;
  if (view.accessor->type != TINYGLTF_TYPE_SCALAR ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    throw Error(view.where + " must be unsigned byte, short or int scalars");
  }
  std::vector<std::uint32_t> out(view.accessor->count);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const unsigned char* p = view.data + i * view.stride;
    std::uint32_t index = 0;
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      index = *p;
    } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      std::uint16_t v;
      std::memcpy(&v, p, sizeof v);
      index = v;
    } else {
      std::memcpy(&index, p, sizeof index);
    }
    if (index >= vertexCount) {
      throw Error(view.where + ": index " + std::to_string(index) + " at position " + std::to_string(i) +
                  " is out of range (the primitive has " + std::to_string(vertexCount) + " vertices)");
    }
    out[i] = index;
  }
  return out;
}

AccessorReader::View AccessorReader::check(int accessorIndex, const std::string& what) const {
  if (accessorIndex < 0 || static_cast<std::size_t>(accessorIndex) >= model_.accessors.size()) {
    throw Error(what + " names accessor " + std::to_string(accessorIndex) + ", which does not exist (" +
                std::to_string(model_.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(accessorIndex)];
  const std::string where = what + " accessor " + std::to_string(accessorIndex);
  if (a.sparse.isSparse) throw Error(where + ": sparse accessors are not supported");
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size()) {
    throw Error(where + ": bufferView " + std::to_string(a.bufferView) + " does not exist");
  }
  const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const std::string viewWhere = where + " (bufferView " + std::to_string(a.bufferView) + ")";
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model_.buffers.size()) {
    throw Error(viewWhere + ": buffer " + std::to_string(bv.buffer) + " does not exist");
  }
  const std::vector<unsigned char>& buffer = model_.buffers[static_cast<std::size_t>(bv.buffer)].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset) {
    throw Error(viewWhere + ": bytes " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) +
                " lie beyond buffer " + std::to_string(bv.buffer) + " of " + std::to_string(buffer.size()) +
                " bytes (missing or short buffer)");
  }
  const int componentBytes = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (componentBytes <= 0 || components <= 0) throw Error(where + ": unknown component type or type");
  const std::size_t elementBytes = static_cast<std::size_t>(componentBytes * components);
  const std::size_t stride = bv.byteStride != 0 ? bv.byteStride : elementBytes;
  if (stride < elementBytes) {
    throw Error(viewWhere + ": byteStride " + std::to_string(stride) + " is smaller than an element (" +
                std::to_string(elementBytes) + " bytes)");
  }
  // count is bounded by the view's bytes first, so the products below cannot overflow
  const bool fits = a.count == 0 || (a.count <= bv.byteLength && a.byteOffset <= bv.byteLength &&
                                     (a.count - 1) * stride + elementBytes <= bv.byteLength - a.byteOffset);
  if (!fits) {
    throw Error(viewWhere + ": " + std::to_string(a.count) + " elements from offset " +
                std::to_string(a.byteOffset) + " do not fit in its " + std::to_string(bv.byteLength) +
                " bytes");
  }
  return {&a, buffer.data() + bv.byteOffset + a.byteOffset, stride, where};
}

}  // namespace voxhap
