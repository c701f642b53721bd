#include "stocs/methods/open3d_methods.h"

#include "open3d_baselines.h"

namespace stocs {

void registerOpen3dMethods() {
  registerMethod("o3d-ransac", makeO3dRansacMethod);
  registerMethod("o3d-fgr", makeO3dFgrMethod);
}

}  // namespace stocs
