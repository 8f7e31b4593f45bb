/*
 * fmu-describe: writes the FMU's descriptions to stdout.
 *
 *   fmu-describe model FILE.c ...   modelDescription.xml (fmu_describe()),
 *                                   with the GUID the FMU checks
 *   fmu-describe build FILE.c ...   sources/buildDescription.xml: how to
 *                                   compile the sources (FMI 2.0.4's build
 *                                   description)
 *
 * The files are paths relative to the FMU's sources/ folder.
 */
#include <stdio.h>
#include <string.h>

#include "fmu_model.h"
#include "uuv_config.h"

static void put_stdout(void *ctx, const char *text) {
    (void)ctx;
    (void)fputs(text, stdout);
}

static void build_description(const char *const *files) {
    printf("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<fmiBuildDescription fmiVersion=\"2.0\">\n"
           "  <BuildConfiguration modelIdentifier=\"uuvsim\" description=\"the %s build; "
           "any C99 compiler, without contraction of floating-point operations\">\n"
           "    <SourceFileSet language=\"C99\" compilerOptions=\"-ffp-contract=off\">\n",
           UUV_NUMERIC_NAME);
    for (size_t k = 0; files[k] != NULL; k++) {
        printf("      <SourceFile name=\"%s\"/>\n", files[k]);
    }
    printf("      <PreprocessorDefinition name=\"UUV_NUMERIC\" value=\"%d\"/>\n"
           "      <IncludeDirectory name=\"src\"/>\n"
           "      <IncludeDirectory name=\"ports/fmu\"/>\n"
           "    </SourceFileSet>\n"
           "    <Library name=\"m\"/>\n"
           "  </BuildConfiguration>\n"
           "</fmiBuildDescription>\n",
           UUV_NUMERIC);
}

int main(int argc, char **argv) {
    if (argc < 2 || (strcmp(argv[1], "model") != 0 && strcmp(argv[1], "build") != 0)) {
        fprintf(stderr, "usage: fmu-describe model|build FILE.c ...\n");
        return 2;
    }
    const char *const *files = (const char *const *)(argv + 2);
    if (strcmp(argv[1], "model") == 0) {
        char guid[FMU_GUID_LEN];
        fmu_guid(guid);
        fmu_describe(put_stdout, NULL, guid, files);
    } else {
        build_description(files);
    }
    return (fflush(stdout) == 0 && !ferror(stdout)) ? 0 : 1;
}
