// The extension gridrt._gridrt: the module's C++ half (python/gridrt/__init__.py is the
// rest). numpy arrays in and out; float32 C-ordered input is read where it lies, any other
// dtype or layout converted once; Python's lock released while the device works. gridrt's
// UsageError (bad shapes, values, options) becomes ValueError, its other errors and
// OpenCL's RuntimeError, each with gridrt's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <CL/opencl.hpp>
#include <memory>
#include <string>
#include <vector>

#include "cl_runtime.h"
#include "errors.h"
#include "image_render.h"
#include "mesh_scene.h"
#include "python_options.h"
#include "scene_queries.h"
#include "scene_source.h"

namespace py = pybind11;
using namespace gridrt;

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

// An array's shape as numpy prints it: (2, 3), (6,).
std::string shapeText(const py::array& a) {
  std::string shape = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
  return shape + (a.ndim() == 1 ? ",)" : ")");
}

// `object` as an array of numbers (booleans, integers, floats), else UsageError.
py::array numbers(const py::object& object, const char* what) {
  py::array any = py::array::ensure(object);
  const char kind = any ? any.dtype().kind() : 'O';
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f')
    throw UsageError(std::string(what) + ": expected an array of numbers");
  return any;
}

// `object` as a C-ordered float32 array of shape rows x 3 (rows < 0: any), else
// UsageError naming `what` (`letter`: how the message names any number of rows).
FloatArray rowsOfThree(const py::object& object, const char* what, py::ssize_t rows = -1,
                       const char* letter = "N") {
  py::array any = numbers(object, what);
  if (any.ndim() != 2 || any.shape(1) != 3 || (rows >= 0 && any.shape(0) != rows))
    throw UsageError(std::string(what) + ": expected shape (" +
                     (rows >= 0 ? std::to_string(rows) : std::string(letter)) + ", 3), got " +
                     shapeText(any));
  return FloatArray::ensure(any);
}

std::shared_ptr<SceneQueries> sceneFromArrays(const py::object& vertices, const py::object& faces,
                                              const std::string& device) {
  FloatArray v = rowsOfThree(vertices, "vertices");
  py::array f_any = py::array::ensure(faces);
  if (!f_any || (f_any.dtype().kind() != 'i' && f_any.dtype().kind() != 'u'))
    throw UsageError("faces: expected an array of integers");
  if (f_any.ndim() != 2 || f_any.shape(1) != 3)
    throw UsageError("faces: expected shape (M, 3), got " + shapeText(f_any));
  IndexArray f = IndexArray::ensure(f_any);
  if (size_t(f.shape(0)) > size_t(INT32_MAX))
    throw UsageError("faces: more than 2^31 - 1 rows");
  MeshScene mesh = meshScene(v.data(), size_t(v.shape(0)), f.data(), size_t(f.shape(0)));
  return std::make_shared<SceneQueries>(std::move(mesh.scene), std::move(mesh.face_of), device);
}

std::shared_ptr<SceneQueries> loadFile(const std::string& path, const std::string& device) {
  if (path.empty()) throw UsageError("load: an empty path");
  const Options o = pythonOptions({path});
  Scene scene;
  loadScene(o, std::nullopt, scene);
  return std::make_shared<SceneQueries>(std::move(scene), std::vector<int32_t>{}, device);
}

// Hits of rays as one count x 4 float32 array holding GrHit records (t, prim's int bits,
// u, v); the Python side views its columns.
py::array traceArrays(SceneQueries& scene, const py::object& origins,
                      const py::object& directions, const py::object& tmax, HitMode mode) {
  FloatArray o = rowsOfThree(origins, "origins");
  FloatArray d = rowsOfThree(directions, "directions", o.shape(0));
  RayArrays rays;
  rays.count = size_t(o.shape(0));
  rays.origins = o.data();
  rays.directions = d.data();
  FloatArray per_ray;
  py::array t_any = numbers(tmax, "tmax");
  if (t_any.ndim() == 0) {
    rays.tmax_all = *FloatArray::ensure(t_any).data();
  } else {
    if (t_any.ndim() != 1 || t_any.shape(0) != o.shape(0))
      throw UsageError("tmax: expected a number or shape (" + std::to_string(o.shape(0)) + ",)");
    per_ray = FloatArray::ensure(t_any);
    rays.tmax = per_ray.data();
  }
  py::array_t<float> hits({py::ssize_t(rays.count), py::ssize_t(4)});
  static_assert(sizeof(GrHit) == 4 * sizeof(float), "GrHit is four 32-bit fields");
  GrHit* out = reinterpret_cast<GrHit*>(hits.mutable_data());
  {
    py::gil_scoped_release unlocked;
    scene.trace(rays, mode, out);
  }
  return std::move(hits);
}

py::tuple renderArray(const std::vector<std::string>& arguments, const SceneQueries* scene) {
  RenderedImage image;
  {
    py::gil_scoped_release unlocked;
    image = renderImage(arguments, scene ? &scene->scene() : nullptr);
  }
  py::array_t<float> pixels({py::ssize_t(image.height), py::ssize_t(image.width),
                             py::ssize_t(image.channels)});
  std::copy(image.pixels.begin(), image.pixels.end(), pixels.mutable_data());
  return py::make_tuple(std::move(pixels), image.warnings);
}

py::list deviceList() {
  py::list out;
  for (const DeviceInfo& d : listDevices()) {
    py::dict row;
    row["id"] = std::to_string(d.platform_index) + ":" + std::to_string(d.device_index);
    row["name"] = d.name;
    row["platform"] = d.platform_name;
    row["type"] = d.type;
    row["compute_units"] = d.compute_units;
    row["global_mem_bytes"] = d.global_mem_bytes;
    out.append(row);
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_gridrt, m) {
  m.doc() = "GridRT's ray queries and renderer (the gridrt package wraps this module)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const cl::Error& e) {
      PyErr_SetString(PyExc_RuntimeError,
                      (std::string("OpenCL error in ") + e.what() + ": " + clErrorName(e.err()))
                          .c_str());
    } catch (const SceneError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const RenderError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<SceneQueries, std::shared_ptr<SceneQueries>>(m, "SceneCore")
      .def_property_readonly("triangle_count", &SceneQueries::triangleCount)
      .def_property_readonly("device", &SceneQueries::device)
      .def_property_readonly("has_camera", [](const SceneQueries& s) { return s.scene().has_camera; })
      .def_property_readonly("warnings", [](const SceneQueries& s) { return s.scene().warnings; })
      .def("intersect",
           [](SceneQueries& s, py::object o, py::object d, py::object tmax) {
             return traceArrays(s, o, d, tmax, HitMode::Closest);
           })
      .def("occluded", [](SceneQueries& s, py::object o, py::object d, py::object tmax) {
        return traceArrays(s, o, d, tmax, HitMode::AnyHit);
      });
  m.def("scene_from_arrays", &sceneFromArrays);
  m.def("load", &loadFile);
  m.def("render", &renderArray);
  m.def("devices", &deviceList);
}
