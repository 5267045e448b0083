"""Writes cie_d65_1nm.csv: CIE standard illuminant D65, 360-830 nm at 1 nm.

Source: colour-science (pip install colour-science; tested with 0.4.7).
- 360-780 nm: CIE 15:2004 Table T.1 (5 nm), colour.SDS_ILLUMINANTS["D65"].
- 785-830 nm: that table ends at 780 nm, so these six values come from the CIE D-series
  formula (CIE 15:2004 Sec. 3.1, S0/S1/S2 basis) at the D65 chromaticity (0.3127, 0.3290),
  colour.sd_CIE_illuminant_D_series; on 360-780 nm it differs from the table by at most 0.35
  (of 100 at 560 nm).
- 1 nm values: linear interpolation between the 5 nm values, the rule CIE 15:2004 gives for
  D-illuminants (and the one rgb2spec_opt and pbrt use).

Run from this folder: python3 make_d65.py
"""

import colour
import numpy as np

table = colour.SDS_ILLUMINANTS["D65"]
xy = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
series = colour.sd_CIE_illuminant_D_series(xy)
coarse_nm = np.arange(360, 831, 5)
coarse = np.array([table[w] if w <= 780 else series[w] for w in coarse_nm])
fine_nm = np.arange(360, 831, 1)
fine = np.interp(fine_nm, coarse_nm, coarse)

with open("cie_d65_1nm.csv", "w") as out:
    out.write("# CIE standard illuminant D65, relative spectral power (100 at 560 nm), 360-830 nm at 1 nm.\n")
    out.write("# 360-780 nm: CIE 15:2004 Table T.1 (5 nm); 785-830 nm: CIE D-series formula at\n")
    out.write("# xy = (0.3127, 0.3290); 1 nm by linear interpolation. Made by make_d65.py from colour-science.\n")
    out.write("wavelength_nm,d65\n")
    for w, v in zip(fine_nm, fine):
        out.write(f"{w},{v:.6f}\n")
