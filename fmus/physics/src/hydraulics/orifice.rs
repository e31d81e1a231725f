//! The regularised turbulent orifice (H2) and the massless junction of a valve port with a
//! counterbalance valve, solved exactly (H6).

/// H2, the flow function of a turbulent orifice with a laminar transition:
/// φ(Δp) = Δp/(Δp² + Δp_t²)^¼ (Pa^½). For |Δp| ≫ Δp_t it is sign(Δp)·√|Δp| (turbulent orifice,
/// Merritt 1967 §3.3 eq. 3-1; Jelali & Kroll 2003 §3.2); near Δp = 0 it is linear with slope
/// 1/√Δp_t, so the flow is Lipschitz in the pressures (finite dQ/dp for RK4). φ is odd and
/// strictly increasing.
pub fn flow_function(dp: f64, transition: f64) -> f64 {
    dp / (dp * dp + transition * transition).sqrt().sqrt()
}

/// A conductance pair: a turbulent coefficient (m³/(s·Pa^½)) and a laminar coefficient
/// (m³/(s·Pa)) acting in parallel between two nodes, with a cap on the turbulent part.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Edge {
    /// K·o (m³/(s·Pa^½)).
    pub turbulent: f64,
    /// Cap of the turbulent flow (m³/s, ≥ 0), or infinity; the flow is clamped to [0, cap] when
    /// `one_way` and to [−cap, cap] otherwise.
    pub cap: f64,
    /// Whether the turbulent path passes flow only from the upstream node to the downstream one.
    pub one_way: bool,
    /// C_leak (m³/(s·Pa)).
    pub laminar: f64,
}

impl Edge {
    /// Flow (m³/s) from the node at `from` to the node at `to` (Pa).
    pub fn flow(&self, from: f64, to: f64, transition: f64) -> f64 {
        let dp = from - to;
        let turbulent = self.turbulent * flow_function(dp, transition);
        let low = if self.one_way { 0.0 } else { -self.cap };
        turbulent.clamp(low, self.cap) + self.laminar * dp
    }
}

/// The flows of one service port between the valve and the chamber.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PortFlow {
    /// Net flow into the chamber (m³/s).
    pub into_chamber: f64,
    /// Pressure of the line between the valve and the chamber (Pa); the chamber pressure when
    /// the line is open to it (no counterbalance valve, or its check valve passing).
    pub line_pressure: f64,
    /// Flow from the supply into the line (m³/s).
    pub from_supply: f64,
    /// Flow from the line to the tank (m³/s).
    pub to_tank: f64,
}

/// H6, the service port: the valve's two edges (supply → line, line → tank) and, if present, a
/// counterbalance valve of turbulent conductance `cbv` (K_cb·o_cb) with a free check valve
/// between the line and the chamber at `p_chamber`. The line holds no volume, so its flows
/// balance: if the valve would push oil into the chamber at the line pressure p_chamber, the
/// check valve opens and the line is the chamber; otherwise the outflow through the poppet
/// equals the valve's flow out of the line, K_cb·o_cb·φ(p_chamber − p_line) = −q_valve(p_line),
/// solved for p_line (both sides monotone: one root, found by bracketing).
pub(crate) fn port_flow(
    supply_edge: &Edge,
    tank_edge: &Edge,
    p_supply: f64,
    p_tank: f64,
    cbv: Option<f64>,
    p_chamber: f64,
    transition: f64,
) -> PortFlow {
    let at = |p_line: f64| {
        let from_supply = supply_edge.flow(p_supply, p_line, transition);
        let to_tank = tank_edge.flow(p_line, p_tank, transition);
        PortFlow { into_chamber: from_supply - to_tank, line_pressure: p_line, from_supply, to_tank }
    };
    let open = at(p_chamber);
    let Some(poppet) = cbv else { return open };
    if open.into_chamber >= 0.0 {
        return open;
    }
    if poppet <= 0.0 {
        // Closed poppet, closed check: the line floats at the pressure where the valve's own
        // flows balance; nothing reaches the chamber.
        let p_line = solve_decreasing(|p| at(p).into_chamber, p_chamber, p_tank);
        return PortFlow { into_chamber: 0.0, ..at(p_line) };
    }
    let balance = |p: f64| at(p).into_chamber + poppet * flow_function(p_chamber - p, transition);
    let p_line = solve_decreasing(balance, p_chamber, p_tank);
    let line = at(p_line);
    PortFlow { into_chamber: -poppet * flow_function(p_chamber - p_line, transition), ..line }
}

/// The root of a strictly decreasing g at or below `high` (g(high) < 0 when called): a bracket
/// [lo, hi] is found by stepping down from `low_guess` with doubling steps, then narrowed by the
/// Illinois variant of regula falsi (bisection when it leaves the bracket). Returns the bracket
/// end with the smaller |g|; never panics.
fn solve_decreasing(g: impl Fn(f64) -> f64, high: f64, low_guess: f64) -> f64 {
    let mut hi = high;
    let mut g_hi = g(hi);
    if g_hi >= 0.0 {
        return hi;
    }
    let mut lo = low_guess.min(high - 1.0);
    let mut step = (high - lo).max(1e5);
    let mut g_lo = g(lo);
    let mut widenings = 0;
    while g_lo < 0.0 && widenings < 60 {
        hi = lo;
        g_hi = g_lo;
        lo -= step;
        step *= 2.0;
        g_lo = g(lo);
        widenings += 1;
    }
    if g_lo < 0.0 {
        return lo;
    }
    let mut side = 0;
    for _ in 0..200 {
        let width = hi - lo;
        if width <= 1e-9 + 1e-15 * hi.abs().max(lo.abs()) {
            break;
        }
        let mut mid = hi - g_hi * (hi - lo) / (g_hi - g_lo);
        if !(mid > lo && mid < hi) {
            mid = 0.5 * (lo + hi);
        }
        let g_mid = g(mid);
        if g_mid == 0.0 {
            return mid;
        }
        if g_mid > 0.0 {
            lo = mid;
            g_lo = g_mid;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = mid;
            g_hi = g_mid;
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
    }
    if g_lo.abs() < g_hi.abs() {
        lo
    } else {
        hi
    }
}
