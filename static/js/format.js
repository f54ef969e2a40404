// Numbers as the pages show them: `digits` significant figures (trailing zeros dropped unless `keepZeros`: "18.00 J"
// says how precisely it is shown), and an exponent ("1.2346e-7", `expDigits` after the point) when the magnitude is
// `large` or more, or under `small`. The one number formatter of the page scripts; each caller states its precision.
export function formatNumber(v, { digits = 6, expDigits = digits - 2, large = 1e6, small = 1e-3, keepZeros = false } = {}) {
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= large || a < small) return v.toExponential(expDigits).replace("e+", "e");
  return keepZeros ? v.toPrecision(digits) : String(+v.toPrecision(digits));
}
