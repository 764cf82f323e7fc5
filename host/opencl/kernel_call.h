// A kernel whose arguments are bound by name and type, not by position. Each kernel gets a
// struct whose members are its parameters, named as in the kernel, and whose inOrder()
// ties them in the kernel's order: the order and the types are written once per kernel,
// beside its struct, and a call names every argument it sets. The kernel's argument
// count is checked against the struct's when the kernel is created, and the OpenCL
// runtime checks each argument's size when it is set.
#pragma once
#include <string>
#include <tuple>

#include "cl_runtime.h"
#include "errors.h"

namespace gridrt {

template <typename Args>
class KernelCall {
 public:
  KernelCall() = default;
  KernelCall(const cl::Program& program, const std::string& name) : kernel_(program, name.c_str()) {
    constexpr size_t kCount = std::tuple_size<decltype(std::declval<const Args&>().inOrder())>();
    const cl_uint count = kernel_.getInfo<CL_KERNEL_NUM_ARGS>();
    if (count != kCount)
      throw RenderError("kernel '" + name + "' takes " + std::to_string(count) +
                        " arguments, its host struct names " + std::to_string(kCount));
  }

  // Sets every argument from `args` and enqueues the kernel over `global` work-items in
  // work-groups of `local`; `done` (may be null) receives the command's event.
  void enqueue(cl::CommandQueue& queue, const cl::NDRange& global, const cl::NDRange& local,
               const Args& args, cl::Event* done = nullptr) {
    std::apply(
        [&](const auto&... values) {
          cl_uint index = 0;
          (kernel_.setArg(index++, values), ...);
        },
        args.inOrder());
    queue.enqueueNDRangeKernel(kernel_, cl::NullRange, global, local, nullptr, done);
  }

 private:
  cl::Kernel kernel_;
};

}  // namespace gridrt
