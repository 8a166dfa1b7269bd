/* The colour-grading chart (seed 004 "Color grading": the LUT is read back from an image an artist
 * graded in an image editor). A chart is the identity 16^3 lattice laid out as 16 tiles of 16x16
 * pixels side by side: blue picks the tile, red runs along x within it and green along y. Lattice
 * index i is stored as the 8-bit display value 17 i (= 255 i / 15), so the identity chart is exact
 * in 8 bits. The chart sits in the top-left corner of its image: hosts write it there (beside or
 * over a screenshot), the plugin's render setting `grading:chart` reads it from there. */
#ifndef OBSCURA_GRADING_CHART_H
#define OBSCURA_GRADING_CHART_H

#include <stdint.h>

/* Seed 004: "16x16x16 LUT proved to be enough". */
#define OBSCURA_GRADING_CHART_LATTICE 16u
#define OBSCURA_GRADING_CHART_WIDTH (OBSCURA_GRADING_CHART_LATTICE * OBSCURA_GRADING_CHART_LATTICE)
#define OBSCURA_GRADING_CHART_HEIGHT OBSCURA_GRADING_CHART_LATTICE

/* The pixel (x, y; y = 0 is the top row) holding lattice point (r, g, b), each 0-15. */
static inline void obscuraGradingChartPixel(uint32_t r, uint32_t g, uint32_t b, uint32_t* x, uint32_t* y) {
    *x = b * OBSCURA_GRADING_CHART_LATTICE + r;
    *y = g;
}

/* The identity chart's 8-bit value of lattice index i. */
static inline uint8_t obscuraGradingChartValue(uint32_t i) {
    return (uint8_t)(i * (255u / (OBSCURA_GRADING_CHART_LATTICE - 1u)));
}

/* The identity chart's 8-bit RGB at pixel (x, y) of the chart: the inverse of the layout above. */
static inline void obscuraGradingChartNeutral(uint32_t x, uint32_t y, uint8_t rgb[3]) {
    rgb[0] = obscuraGradingChartValue(x % OBSCURA_GRADING_CHART_LATTICE);
    rgb[1] = obscuraGradingChartValue(y);
    rgb[2] = obscuraGradingChartValue(x / OBSCURA_GRADING_CHART_LATTICE);
}

#endif
