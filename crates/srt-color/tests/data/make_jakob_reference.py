"""Writes the independent reference for crates/srt-color/tests/spectral.rs.

Uses colour-science's own implementation of Jakob & Hanika 2019 (colour.recovery), its own CIE
1931 table, D65 and Planck's law; nothing from srt. Tested with colour-science 0.4.7:

    python3 -m venv /tmp/cs && /tmp/cs/bin/pip install colour-science
    cd crates/srt-color/tests/data && /tmp/cs/bin/python make_jakob_reference.py

jakob_reference.csv, one row per ColorChecker patch and Doppler pair:
  patch, name, linear sRGB (r, g, b) in [0, 1], d_in, d_out, the coefficients colour-science fits
  (c0, c1, c2 for lambda in nm), and the CIELAB (L, a, b) of the light the patch reflects.

The reflected light follows docs/colour.md: a black body of TEMPERATURE_K, seen by the surface
with d_in and the surface seen with d_out, gives at observed wavelength l the spectral radiance
R(d_out * l) * B(l, d_in * d_out * T), with R held at its 360 nm / 830 nm value outside
360-830 nm (srt's out-of-domain policy). CIELAB is relative to a perfect white reflector in the
same place: the black body at d_in * d_out * T, normalised to Y = 1.

ciede2000_reference.csv: pairs of CIELAB colours and colour-science's CIEDE2000 difference, to
check the test's own CIEDE2000.
"""

import colour
import numpy as np

TEMPERATURE_K = 6504.0
DOPPLER_PAIRS = [(1.0, 0.5), (1.0, 0.8), (1.0, 1.25), (1.0, 2.0), (0.7, 1.25)]

shape = colour.SpectralShape(360, 830, 1)
cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
d65 = colour.SDS_ILLUMINANTS["D65"].copy().align(shape)
wavelengths = shape.wavelengths
cmf = cmfs.values  # (471, 3)

# ColorChecker 24 (X-Rite, after November 2014), xyY under D50, adapted to D65 with Bradford and
# expressed in linear sRGB, clipped to [0, 1] (patch 18, cyan, lies slightly outside sRGB).
checker = colour.CCS_COLOURCHECKERS["ColorChecker24 - After November 2014"]
srgb = colour.RGB_COLOURSPACES["sRGB"]


def reflected_lab(coefficients, d_in, d_out):
    c0, c1, c2 = coefficients
    shifted = np.clip(d_out * wavelengths, 360.0, 830.0)
    u = c0 * shifted**2 + c1 * shifted + c2
    reflectance = 0.5 + u / (2.0 * np.sqrt(1.0 + u**2))
    radiance = colour.colorimetry.planck_law(wavelengths * 1e-9, d_in * d_out * TEMPERATURE_K)
    xyz = (reflectance * radiance) @ cmf
    white = radiance @ cmf
    return colour.XYZ_to_Lab(xyz / white[1], colour.XYZ_to_xy(white))


with open("jakob_reference.csv", "w") as out:
    out.write(
        "# Independent reference from colour-science %s, made by make_jakob_reference.py; "
        "black body %.0f K.\n" % (colour.__version__, TEMPERATURE_K)
    )
    out.write("patch,name,r,g,b,d_in,d_out,c0,c1,c2,L,a,b_star\n")
    for index, (name, xyY) in enumerate(checker.data.items()):
        xyz_d50 = colour.xyY_to_XYZ(xyY)
        rgb = colour.XYZ_to_RGB(
            xyz_d50,
            srgb,
            illuminant=checker.illuminant,
            chromatic_adaptation_transform="Bradford",
        )
        rgb = np.clip(rgb, 0.0, 1.0)
        xyz = colour.RGB_to_XYZ(rgb, srgb)
        coefficients, _error = colour.recovery.find_coefficients_Jakob2019(
            xyz, cmfs, d65
        )
        for d_in, d_out in DOPPLER_PAIRS:
            lab = reflected_lab(coefficients, d_in, d_out)
            out.write(
                f"{index + 1},{name.replace(',', ' ')},{rgb[0]:.9f},{rgb[1]:.9f},{rgb[2]:.9f},"
                f"{d_in},{d_out},{coefficients[0]:.12e},{coefficients[1]:.12e},"
                f"{coefficients[2]:.12e},{lab[0]:.6f},{lab[1]:.6f},{lab[2]:.6f}\n"
            )

rng = np.random.default_rng(2019)
with open("ciede2000_reference.csv", "w") as out:
    out.write(
        "# CIEDE2000 from colour-science %s (colour.delta_E, method 'CIE 2000'), made by "
        "make_jakob_reference.py.\n" % colour.__version__
    )
    out.write("L1,a1,b1,L2,a2,b2,delta_e\n")
    # Sharma, Wu & Dalal (2005) pairs exercising the hue-angle cases, then random pairs.
    pairs = [
        ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485]),
        ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0]),
        ([50.0, 2.49, -0.001], [50.0, -2.49, 0.0009]),
        ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0]),
        ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387]),
        ([22.7233, 20.0904, -46.694], [23.0331, 14.973, -42.5619]),
        ([2.0776, 0.0795, -1.135], [0.9033, -0.0636, -0.5514]),
    ]
    for _ in range(40):
        a = rng.uniform([0, -100, -100], [100, 100, 100])
        b = a + rng.normal(0.0, 4.0, 3)
        pairs.append((list(a), list(b)))
    for lab1, lab2 in pairs:
        d = colour.delta_E(np.array(lab1), np.array(lab2), method="CIE 2000")
        out.write(",".join(f"{v:.6f}" for v in [*lab1, *lab2]) + f",{float(d):.6f}\n")
