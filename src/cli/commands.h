/* commands.h — the subcommands of the shapedem program. */
#ifndef SD_CLI_COMMANDS_H
#define SD_CLI_COMMANDS_H

#include <signal.h>

#include <shapedem/shapedem.h>

/* Prints "shapedem: file:line: key: message" and returns exit status 2. */
int sd_cli_fail_input(const sd_error *err);
/* Set by the first SIGINT/SIGTERM (sd_cli_on_signal, main.c): the run stops
 * after the step in progress with a final checkpoint; a second signal ends
 * the process at once with the signal's default action. */
extern volatile sig_atomic_t sd_cli_interrupted;
void sd_cli_on_signal(int sig);
int sd_cmd_shape(int argc, char **argv);
/* `shapedem shape fit-fourier` (cli/fit_fourier.c) */
int sd_cmd_fit_fourier(int argc, char **argv);
/* `shapedem info` (cli/info_cmd.c): a checkpoint's summary or its particles as CSV */
int sd_cmd_info(int argc, char **argv);
/* `shapedem render` (cli/render_cmd.c, src/render/) */
int sd_cmd_render(int argc, char **argv);

#endif
