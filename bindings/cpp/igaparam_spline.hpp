// igaparam: the C++17 wrapper of the spline handle (igaparam_spline*): igaparam::Spline, a cubic
// THB-spline map fitted to a domain, with its queries, Bézier extraction, refinement, refits and
// certified validity. Included by igaparam.hpp; include that one.

#ifndef IGAPARAM_SPLINE_HPP
#define IGAPARAM_SPLINE_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "igaparam.hpp"

namespace igaparam {

/// The Bézier extraction of one element: N_functions[i] = Σ_k op[i·4^d + k] B_k on the element.
struct Extraction {
  std::vector<std::size_t> functions;  ///< global indices of the functions non-zero on it
  std::vector<double> op;              ///< functions.size() × 4^d, row-major
};

/// The basis functions non-zero at a point.
struct BasisValues {
  std::vector<std::size_t> functions;  ///< global indices
  std::vector<double> values;          ///< one per function
  std::vector<double> gradients;       ///< d per function, with respect to the parameters
};

/// A cubic THB-spline map S: [0,1]^d → Ω (owner of an igaparam_spline*). Move-only; clone() copies.
/// Points are flat arrays, d doubles each.
class Spline : public detail::Handle<igaparam_spline, igaparam_spline_free> {
 public:
  /// Fits the spline map of a built domain; `report` may be NULL.
  static Spline fit(const igaparam_domain* domain, igaparam_fit_report* report = nullptr) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_fit_domain(domain, &handle, report));
    return Spline(handle);
  }

  /// Fits the spline map of a built domain; `report` may be NULL.
  static Spline fit(const Domain& domain, igaparam_fit_report* report = nullptr) {
    return fit(domain.get(), report);
  }

  /// Fits the spline map of a built domain with `options` (igaparam_spline_fit_domain_with:
  /// fit rule, certification, untangling, smoothing, threads; `options.progress`, a C callback,
  /// is used as given); `report` may be NULL.
  static Spline fit(const Domain& domain, const igaparam_fit_options& options,
                    igaparam_fit_report* report = nullptr) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_fit_domain_with(domain.get(), &options, &handle, report));
    return Spline(handle);
  }

  /// Fits as above, calling `progress` (instead of options.progress) with IGAPARAM_STAGE_FIT,
  /// _UNTANGLING and _SMOOTHING; returning false cancels. If `progress` throws, the fit is
  /// cancelled and the exception is rethrown.
  static Spline fit(const Domain& domain, igaparam_fit_options options, const Progress& progress,
                    igaparam_fit_report* report = nullptr) {
    detail::ProgressTrampoline trampoline{&progress, nullptr};
    options.progress = &detail::ProgressTrampoline::call;
    options.progress_user = &trampoline;
    igaparam_spline* handle = nullptr;
    const igaparam_status status =
        igaparam_spline_fit_domain_with(domain.get(), &options, &handle, report);
    if (trampoline.exception) {
      std::rethrow_exception(trampoline.exception);
    }
    detail::check(status);
    return Spline(handle);
  }

  /// The adaptive loop: fits the map of a built domain, refines its T-mesh where the map is of
  /// poor quality, optimizes and refits (igaparam_domain_fit_adaptive); the domain keeps the
  /// refined T-mesh. `report` may be NULL.
  static Spline fit_adaptive(Domain& domain,
                             const igaparam_adapt_options& options = igaparam_adapt_options_default(),
                             igaparam_adapt_report* report = nullptr) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_domain_fit_adaptive(domain.get(), &options, &handle, report));
    return Spline(handle);
  }

  /// Reads a map written by write_gismo.
  static Spline read_gismo(const std::string& path) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_read_gismo(path.c_str(), &handle));
    return Spline(handle);
  }

  /// Takes ownership of a handle (may be NULL).
  explicit Spline(igaparam_spline* handle) noexcept : Handle(handle) {}

  /// An independent copy.
  Spline clone() const {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_clone(handle_, &handle));
    return Spline(handle);
  }

  std::size_t dimension() const { return query(igaparam_spline_dimension); }
  std::size_t basis_count() const { return query(igaparam_spline_basis_count); }
  std::size_t element_count() const { return query(igaparam_spline_element_count); }

  /// Control points, basis_count() × d.
  std::vector<double> control_points() const {
    return copied(basis_count() * dimension(), igaparam_spline_copy_control_points);
  }

  /// Greville points of the basis functions, basis_count() × d.
  std::vector<double> greville_points() const {
    return copied(basis_count() * dimension(), igaparam_spline_copy_greville_points);
  }

  /// Level of every element.
  std::vector<std::uint8_t> element_levels() const {
    std::vector<std::uint8_t> levels(element_count());
    detail::check(igaparam_spline_copy_elements(handle_, levels.data(), nullptr, levels.size()));
    return levels;
  }

  /// Box of every element, element_count() × 2d (lower corner, then upper corner).
  std::vector<double> element_bounds() const {
    const std::size_t n = element_count();
    std::vector<double> bounds(2 * dimension() * n);
    detail::check(igaparam_spline_copy_elements(handle_, nullptr, bounds.data(), n));
    return bounds;
  }

  /// The Bézier extraction of element `e`.
  Extraction extraction(std::size_t e) const {
    std::size_t m = 0;
    detail::check(igaparam_spline_element_function_count(handle_, e, &m));
    Extraction x{std::vector<std::size_t>(m), std::vector<double>(m * bernstein_count())};
    detail::check(igaparam_spline_copy_element_extraction(handle_, e, x.functions.data(), m, x.op.data(),
                                                          x.op.size()));
    return x;
  }

  /// S at the parametric points `params` (n × d in [0,1]^d); `jacobians`, if given, receives
  /// n × d × d row-major entries ∂S_i/∂u_j.
  std::vector<double> evaluate(const std::vector<double>& params, std::vector<double>* jacobians = nullptr) const {
    const std::size_t d = dimension(), n = count(params, d);
    std::vector<double> points(n * d);
    if (jacobians) jacobians->assign(n * d * d, 0.0);
    detail::check(igaparam_spline_evaluate(handle_, n, params.data(), points.data(),
                                           jacobians ? jacobians->data() : nullptr));
    return points;
  }

  /// Mean ratio of the Jacobian at the parametric points `params` (n × d).
  std::vector<double> mean_ratio(const std::vector<double>& params) const {
    const std::size_t n = count(params, dimension());
    std::vector<double> q(n);
    detail::check(igaparam_spline_mean_ratio(handle_, n, params.data(), q.data()));
    return q;
  }

  /// Parametric points of the physical points `points` (n × d): NaN where `found` is 0.
  std::vector<double> invert(const std::vector<double>& points, std::vector<int>* found = nullptr,
                             std::uint32_t samples = 4) const {
    const std::size_t d = dimension(), n = count(points, d);
    std::vector<double> params(n * d);
    if (found) found->assign(n, 0);
    detail::check(igaparam_spline_invert(handle_, n, points.data(), samples, params.data(),
                                         found ? found->data() : nullptr));
    return params;
  }

  /// The basis functions non-zero at the parametric point `param` (d values).
  BasisValues basis_at(const std::vector<double>& param) const {
    const std::size_t d = dimension();
    detail::require(param.size() == d, "igaparam::Spline::basis_at: param must hold d values");
    std::size_t m = 0;
    detail::check(igaparam_spline_basis_count_at(handle_, param.data(), &m));
    BasisValues b{std::vector<std::size_t>(m), std::vector<double>(m), std::vector<double>(m * d)};
    detail::check(igaparam_spline_basis_at(handle_, param.data(), &m, b.functions.data(), b.values.data(),
                                           b.gradients.data(), m));
    return b;
  }

  /// Recomputes the control points from the domain's T-mesh after Domain::update, in the same
  /// space and by the rule of the first fit (igaparam_spline_refit).
  igaparam_refit_report refit(const Domain& domain) {
    igaparam_refit_report report{};
    detail::check(igaparam_spline_refit(handle_, domain.get(), &report));
    return report;
  }

  /// The first-order motion of the control points (d per control point) of a refit to
  /// `domain` for a motion of its boundary vertices (d per vertex; inner rows ignored), through
  /// the T-mesh's optimum and the fit rule (igaparam_spline_tangent, with its conditions).
  std::vector<double> tangent(const Domain& domain, const std::vector<double>& dx_boundary) const {
    std::vector<double> dp(basis_count() * dimension());
    detail::check(igaparam_spline_tangent(handle_, domain.get(), dx_boundary.size(), dx_boundary.data(),
                                          dp.size(), dp.data()));
    return dp;
  }

  /// The total derivative of a scalar J with respect to the boundary vertices of `domain`'s
  /// T-mesh (d per vertex, 0 at inner ones), given dJ/dP (d per control point); the transpose
  /// of tangent (igaparam_spline_adjoint).
  std::vector<double> adjoint(const Domain& domain, const std::vector<double>& dj_dp) const {
    std::vector<double> out(domain.vertex_count() * dimension());
    detail::check(igaparam_spline_adjoint(handle_, domain.get(), dj_dp.size(), dj_dp.data(), out.size(),
                                          out.data()));
    return out;
  }

  /// The first-order motion of the control points (d per control point) of a refit to
  /// `domain` for a motion of its boundary curves' or surfaces' control points (d per control
  /// point, Domain::control_count of them; igaparam_spline_tangent_controls).
  std::vector<double> tangent_controls(const Domain& domain, const std::vector<double>& dc) const {
    std::vector<double> dp(basis_count() * dimension());
    detail::check(igaparam_spline_tangent_controls(handle_, domain.get(), dc.size(), dc.data(), dp.size(),
                                                   dp.data()));
    return dp;
  }

  /// The total derivative of a scalar J with respect to the control points of `domain`'s
  /// boundary curves or surfaces, given dJ/dP; the transpose of tangent_controls
  /// (igaparam_spline_adjoint_controls).
  std::vector<double> adjoint_controls(const Domain& domain, const std::vector<double>& dj_dp) const {
    std::vector<double> out(domain.control_count() * dimension());
    detail::check(igaparam_spline_adjoint_controls(handle_, domain.get(), dj_dp.size(), dj_dp.data(),
                                                   out.size(), out.data()));
    return out;
  }

  /// The rule the control points come from (that of the first fit).
  igaparam_fit_rule fit_rule() const {
    igaparam_fit_rule rule = IGAPARAM_FIT_INTERPOLATION;
    detail::check(igaparam_spline_fit_rule(handle_, &rule));
    return rule;
  }

  /// Refines the marked elements (all when empty), the map staying the same.
  igaparam_fit_report refine(const std::vector<std::size_t>& elements = {}) {
    igaparam_fit_report report{};
    detail::check(igaparam_spline_refine(handle_, elements.size(), elements.empty() ? nullptr : elements.data(),
                                         &report));
    return report;
  }

  /// Certified validity and quality; `element_quality`, if given, receives each element's
  /// smallest sampled mean ratio.
  igaparam_validity_report check_validity(const igaparam_validity_options& options = igaparam_validity_options_default(),
                                          std::vector<double>* element_quality = nullptr) const {
    igaparam_validity_report report{};
    const std::size_t n = element_quality ? element_count() : 0;
    if (element_quality) element_quality->assign(n, 0.0);
    detail::check(igaparam_spline_check_validity(handle_, &options, &report, nullptr,
                                                 element_quality ? element_quality->data() : nullptr, n));
    return report;
  }

  /// A certified lower bound of the map's mean ratio and the sampled minimum it is refined
  /// towards: the true minimum lies in `[lower_bound, sampled_min]`.
  igaparam_quality_bound_report quality_bound(
      const igaparam_quality_bound_options& options = igaparam_quality_bound_options_default()) const {
    igaparam_quality_bound_report report{};
    detail::check(igaparam_spline_quality_bound(handle_, &options, &report));
    return report;
  }

  /// Writes the map sampled on `samples`^d sub-cells per element as .vtu.
  void write_vtu(const std::string& path, std::uint32_t samples = 4) const {
    detail::check(igaparam_spline_write_vtu(handle_, path.c_str(), samples));
  }

  /// Writes the map as G+Smo XML.
  void write_gismo(const std::string& path) const { detail::check(igaparam_spline_write_gismo(handle_, path.c_str())); }

 private:
  std::size_t query(igaparam_status (*getter)(const igaparam_spline*, std::size_t*)) const {
    std::size_t value = 0;
    detail::check(getter(handle_, &value));
    return value;
  }

  std::vector<double> copied(std::size_t n, igaparam_status (*copy)(const igaparam_spline*, double*, std::size_t)) const {
    std::vector<double> values(n);
    detail::check(copy(handle_, values.data(), values.size()));
    return values;
  }

  std::size_t bernstein_count() const { return dimension() == 2 ? 16 : 64; }

  static std::size_t count(const std::vector<double>& points, std::size_t d) {
    detail::require(points.size() % d == 0, "igaparam::Spline: point arrays must hold d values per point");
    return points.size() / d;
  }

};

}  // namespace igaparam

#endif  // IGAPARAM_SPLINE_HPP
