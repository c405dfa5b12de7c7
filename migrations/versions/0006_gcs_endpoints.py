"""gcs_endpoints: the ground stations a vehicle's MAVLink is relayed to

Revision ID: 0006
Revises: 0005
Create Date: 2026-11-27

"""
from typing import Sequence, Union

from alembic import op
import sqlalchemy as sa


# revision identifiers, used by Alembic.
revision: str = '0006'
down_revision: Union[str, Sequence[str], None] = '0005'
branch_labels: Union[str, Sequence[str], None] = None
depends_on: Union[str, Sequence[str], None] = None


def upgrade() -> None:
    """Upgrade schema."""
    with op.batch_alter_table('vehicles') as batch:
        batch.add_column(sa.Column('gcs_endpoints', sa.JSON(), nullable=False, server_default='[]'))


def downgrade() -> None:
    """Downgrade schema."""
    with op.batch_alter_table('vehicles') as batch:
        batch.drop_column('gcs_endpoints')
