// render/gl/passes/volume_kernel.glsl - the SPH kernels of render/sph_kernel.h for the volume
// march: h^3 W(q h, h) and its slope in q, and the support in units of h, for the kernel u_kernel
// names (its SphKernel value). The constants and forms are those of sph_kernel.h, written once
// here for two types: float for the samples' sums (vm_kernel_shape, vm_kernel_slope), double
// for the iso hits' gradients (vm_kernel_shape_d, vm_kernel_slope_d), whose Shepard quotient
// cancels what float would keep. test_volume_gl holds the pictures to the double reference.
#define VM_PI 3.14159265358979lf

#define VM_KERNELS(T, SHAPE, SLOPE)                                                          \
  T SHAPE(T q) {                                                                             \
    T zero = T(0.0);                                                                         \
    if (u_kernel == 1u) {                                                                    \
      T t = max(T(1.0) - T(0.5) * q, zero);                                                  \
      return (T(21.0) / (T(16.0) * T(VM_PI))) * (t * t) * (t * t) * (T(2.0) * q + T(1.0));   \
    }                                                                                        \
    if (u_kernel == 2u) {                                                                    \
      T a = max(T(3.0) - q, zero), b = max(T(2.0) - q, zero), c = max(T(1.0) - q, zero);     \
      return (T(1.0) / (T(120.0) * T(VM_PI))) *                                              \
             (a * a * a * a * a - T(6.0) * b * b * b * b * b + T(15.0) * c * c * c * c * c); \
    }                                                                                        \
    if (u_kernel == 3u) {                                                                    \
      T t = max(T(1.0) - q * q, zero);                                                       \
      return (T(315.0) / (T(64.0) * T(VM_PI))) * t * t * t;                                  \
    }                                                                                        \
    T a = max(T(2.0) - q, zero), b = max(T(1.0) - q, zero);                                  \
    return (T(0.25) / T(VM_PI)) * (a * a * a - T(4.0) * b * b * b);                          \
  }                                                                                          \
  T SLOPE(T q) {                                                                             \
    T zero = T(0.0);                                                                         \
    if (u_kernel == 1u) {                                                                    \
      if (q >= T(2.0)) return zero;                                                          \
      T t = T(1.0) - T(0.5) * q;                                                             \
      return T(21.0) / (T(16.0) * T(VM_PI)) * (T(-5.0) * q) * t * t * t;                     \
    }                                                                                        \
    if (u_kernel == 2u) {                                                                    \
      if (q >= T(3.0)) return zero;                                                          \
      T a = max(T(3.0) - q, zero), b = max(T(2.0) - q, zero), c = max(T(1.0) - q, zero);     \
      return T(-5.0) / (T(120.0) * T(VM_PI)) *                                               \
             (a * a * a * a - T(6.0) * b * b * b * b + T(15.0) * c * c * c * c);             \
    }                                                                                        \
    if (u_kernel == 3u) {                                                                    \
      if (q >= T(1.0)) return zero;                                                          \
      T t = T(1.0) - q * q;                                                                  \
      return T(315.0) / (T(64.0) * T(VM_PI)) * (T(-6.0) * q) * t * t;                        \
    }                                                                                        \
    if (q < T(1.0)) return (T(-3.0) * q + T(2.25) * q * q) / T(VM_PI);                       \
    if (q < T(2.0)) return T(-0.75) / T(VM_PI) * (T(2.0) - q) * (T(2.0) - q);                \
    return zero;                                                                             \
  }

VM_KERNELS(float, vm_kernel_shape, vm_kernel_slope)
VM_KERNELS(double, vm_kernel_shape_d, vm_kernel_slope_d)

float vm_kernel_support() { return u_kernel == 2u ? 3.0 : (u_kernel == 3u ? 1.0 : 2.0); }
