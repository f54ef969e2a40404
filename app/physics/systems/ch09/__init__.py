"""Chapter 9 systems: Hamilton's principle and Ritz series, Hamilton's and Routh's equations, Gibbs–Appell and Kane."""
