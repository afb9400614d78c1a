#include "flatten/face_cones.h"

#include <initializer_list>

namespace liftmap::subproblem {

void face_cones(const FaceSetup& fs, const Settings& st, FaceCones& fc) {
  fc = FaceCones{};
  const int ke = st.p_inf ? kT : kE;
  auto add = [&](int dim, std::initializer_list<int> vars) -> Cone& {
    Cone& k = fc.cone[static_cast<size_t>(fc.n++)];
    k.dim = dim;
    for (const int v : vars) k.var[static_cast<size_t>(k.n++)] = v;
    return k;
  };
  {  // c >= |(gamma, delta)|, variables (c, gamma, delta)
    Cone& k = add(3, {kC, 2, 3});
    k.A(0, 0) = k.A(1, 1) = k.A(2, 2) = 1;
  }
  if (fs.ghost()) {
    Cone& k1 = add(3, {kC, 0, 1});  // bound - c >= |(alpha, beta)|
    k1.A(0, 0) = -1;
    k1.A(1, 1) = k1.A(2, 2) = 1;
    k1.b(0) = fs.bound;
    Cone& k2 = add(1, {0, 1, kC});  // m = l - c >= 0
    k2.A(0, 0) = fs.cs;
    k2.A(0, 1) = fs.sn;
    k2.A(0, 2) = -1;
    return;
  }
  // The variable that bounds |(alpha, beta)| + c: r for eq. 3, the epigraph variable for eq. 2.
  const int top = st.h_max ? ke : kR;
  Cone& k1 = add(3, {top, kC, 0, 1});  // top - c >= |(alpha, beta)|
  k1.A(0, 0) = 1;
  k1.A(0, 1) = -1;
  k1.A(1, 2) = k1.A(2, 3) = 1;
  // The variable that bounds 1 / m: s for eq. 3, the epigraph variable for eq. 2. Rotated cone inv m >= 1 as
  // (inv + m, inv - m, 2), m = alpha cos + beta sin - c.
  const int inv = st.h_max ? ke : kS;
  Cone& k2 = add(3, {inv, 0, 1, kC});
  k2.A.row(0) << 1, fs.cs, fs.sn, -1;
  k2.A.row(1) << 1, -fs.cs, -fs.sn, 1;
  k2.b(2) = 2;
  if (!st.h_max) {
    Cone& k3 = add(3, {ke, kR, kS});  // e >= |(r, s)|
    k3.A(0, 0) = k3.A(1, 1) = k3.A(2, 2) = 1;
  }
}

}  // namespace liftmap::subproblem
