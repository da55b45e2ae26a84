/* rough_energy.c: the table behind chapter 17's plot of the light a rough conductor loses (make
 * rough-energy, docs/17-rough.md): for roughness 0 to 1, the share of light a GGX conductor of
 * reflectance 1 fails to reflect, single scattering only, by common/microfacet.c's numerical integral.
 *
 * Usage: rough-energy. Prints a line per roughness: roughness, alpha, the loss seen from straight above
 * (mu = cos theta = 1), at mu 0.5, at mu 0.1, and averaged over the hemisphere as a white furnace sees
 * it (1 - E_avg, E_avg = 2 * integral of E(mu) mu dmu). Exit status 0, 2 for a bad command line, 3 when
 * the output cannot be written. */
#include <math.h>
#include <stdio.h>

#include "microfacet.h"

#define ROUGHNESS_STEPS 20 /* lines: roughness 0, 0.05, ..., 1 */
#define ALBEDO_STEPS 256   /* microfacet_albedo's points a side, for one direction */
#define AVERAGE_STEPS 32   /* directions mu in the hemisphere's average ... */
#define AVERAGE_ALBEDO_STEPS 128 /* ... and microfacet_albedo's points a side for each */

static double loss(const struct microfacet_lobe *l, double mu, int steps) {
    vec3 wo = vec3_make(sqrt(1.0 - mu * mu), 0.0, mu);
    return 1.0 - microfacet_albedo(l, wo, steps).x;
}

int main(int argc, char **argv) {
    if (argc != 1) {
        fprintf(stderr, "usage: %s   (prints chapter 17's table of energy loss against roughness)\n", argv[0]);
        return 2;
    }
    printf("# roughness alpha loss(mu=1) loss(mu=0.5) loss(mu=0.1) loss(average)\n");
    for (int k = 0; k <= ROUGHNESS_STEPS; k++) {
        double roughness = (double)k / ROUGHNESS_STEPS, alpha = microfacet_alpha(roughness);
        struct microfacet_lobe l = microfacet_conductor_lobe(vec3_make(1.0, 1.0, 1.0), alpha);
        double average = 0.0;
        for (int j = 0; j < AVERAGE_STEPS; j++) {
            double mu = (j + 0.5) / AVERAGE_STEPS;
            average += 2.0 * mu * (1.0 - loss(&l, mu, AVERAGE_ALBEDO_STEPS)) / AVERAGE_STEPS;
        }
        printf("%.2f %.4f %.4f %.4f %.4f %.4f\n", roughness, alpha, loss(&l, 1.0, ALBEDO_STEPS),
               loss(&l, 0.5, ALBEDO_STEPS), loss(&l, 0.1, ALBEDO_STEPS), 1.0 - average);
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        perror("rough-energy: cannot write the table");
        return 3;
    }
    return 0;
}
