// Error reporting: one clear message per failure, a non-zero exit on every rank, never a hang.
#pragma once

#include <petscsys.h>

#include <functional>
#include <string>

namespace signorini {

/// Installs the error handler that prints "signorini: error: <message>" once (rank 0 for collective errors) and
/// aborts the MPI job for errors raised on a single rank, so that no rank waits forever (work that rank 0 does alone
/// runs in RunOnRoot, which raises its errors on every rank instead). Call once on all ranks,
/// before PetscInitialize so that errors in reading -options_file are reported the same way.
[[nodiscard]] PetscErrorCode InstallErrorHandler();
/// The options files of the run ("a.yml, b.txt", OptionsFileProblem), named by the handler's message when
/// PetscInitialize cannot read one of them.
void SetOptionsFiles(const std::string &files);
/// Names the directory that this rank made for the run's output (DIR/incomplete; "" once the output is published, and
/// on the ranks that made none), which a failure must not leave behind: main removes it when Run fails, the error
/// handler before it aborts the job. Removes nothing beside it (an earlier good output in DIR stays as it is).
/// made: how many of dir's parents the run made (DIR and those above it), removed too, each when it is left empty.
void RemoveOnFailure(const std::string &dir, int made = 0);
/// Removes the directories that RemoveOnFailure named, if any, and forgets them. Local (no communication).
void RemoveFailedOutput();

/// Collective check of a condition that may hold on some ranks only: if any rank has ok == false, every rank raises
/// PETSC_ERR_USER_INPUT with the message of the lowest failing rank. Call on all ranks of comm together.
[[nodiscard]] PetscErrorCode CheckCollective(MPI_Comm comm, bool ok, const std::string &message);

/// Broadcasts a status/message pair from rank 0 and raises the error on all ranks when it is not empty.
[[nodiscard]] PetscErrorCode RaiseFromRoot(MPI_Comm comm, const std::string &message_on_root);

/// Runs work on rank 0 of comm alone (the other ranks do not call it) and raises the first PETSc error it raises,
/// with its code, message and place, on every rank of comm: the error handler reports it once and every rank unwinds
/// (an error of rank 0 alone would abort the job). Neither prints the error on rank 0 nor aborts while work runs; a C++
/// exception from work is an error too. Call on all ranks of comm together; work must not communicate on comm.
[[nodiscard]] PetscErrorCode RunOnRoot(MPI_Comm comm, const std::function<PetscErrorCode()> &work);

/// Gives every rank of comm the text of rank root. Collective.
[[nodiscard]] PetscErrorCode Broadcast(MPI_Comm comm, PetscMPIInt root, std::string &text);

} // namespace signorini
