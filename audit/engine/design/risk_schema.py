"""The columns of the files a design-level audit at a site adds (``margins --hazard``), their
unit and meaning (``columns.json`` beside the files)."""

#: Columns of ``risk.csv``, ``risk_alpha.csv`` and ``hazard.csv``: unit and meaning
#: (``columns.json``).
RISK_GUIDE = {
    "risk.csv": {
        "alpha_deg": ("deg", "slenderness α"),
        "size_s": ("s", "block size 2π/p"),
        "width_m": ("m", "full base width of a block given by its dimensions (blocks); "
                         "empty for a grid block"),
        "height_m": ("m", "full height of a block given by its dimensions (blocks); empty "
                          "for a grid block"),
        "im": ("text", "intensity measure of the hazard curve and the fragility"),
        "annual_rate_fit": ("1/yr", "mean annual rate of overturning λ_ov, lognormal fit"),
        "annual_rate_fit_upper": ("1/yr", "the most λ_ov can be where the hazard curve stops"),
        "p50_fit": ("-", "probability of overturning in 50 years, 1 − exp(−50 λ_ov), fit"),
        "im_low_90_g": ("g", "5 % point of λ_ov along the intensity (fit)"),
        "im_high_90_g": ("g", "95 % point of λ_ov along the intensity (fit); inf above the "
                              "curve's last level"),
        "annual_rate_stripes": ("1/yr", "λ_ov from the counted stripe shares"),
        "p50_stripes": ("-", "P in 50 years from the counted stripe shares"),
        "truncated": ("bool", "the hazard curve stops below the fragility's median"),
    },
    "risk_alpha.csv": {
        "procedure": ("text", "guideline procedure (the α it accepts, from required_alpha.csv), "
                              "or exact@risk (the smallest α meeting the risk target)"),
        "size_s": ("s", "block size 2π/p"),
        "required_alpha_deg": ("deg", "the α; for exact@risk ln P interpolated between the "
                                      "grid's α; empty when none of the grid's α meets it"),
        "p50": ("-", "P of overturning in 50 years of the block of this size and α (ln P "
                     "interpolated in α on the grid; empty outside it)"),
    },
    "hazard.csv": {
        "im_g": ("g", "intensity level of the site's hazard curve"),
        "annual_rate": ("1/yr", "mean annual rate of exceeding it (as read from the hazard file)"),
    },
}


__all__ = ["RISK_GUIDE"]
