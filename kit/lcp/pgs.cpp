#include "kit/lcp/pgs.hpp"

namespace pb::lcp {

PgsResult pgs(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
              Eigen::Ref<Eigen::VectorXd> z, const PgsSettings& settings) {
  return detail::pgs_impl(a, q, z, settings);
}

}  // namespace pb::lcp
