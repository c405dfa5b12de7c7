"""vehicle_plan_extras: the rally points and geofence circles of each vehicle's last .plan

Revision ID: 0010
Revises: 0009
Create Date: 2026-11-29

"""
from typing import Sequence, Union

from alembic import op
import sqlalchemy as sa


# revision identifiers, used by Alembic.
revision: str = '0010'
down_revision: Union[str, Sequence[str], None] = '0009'
branch_labels: Union[str, Sequence[str], None] = None
depends_on: Union[str, Sequence[str], None] = None


def upgrade() -> None:
    """Upgrade schema."""
    op.create_table(
        'vehicle_plan_extras',
        sa.Column('vehicle_id', sa.String(length=32), nullable=False),
        sa.Column('rally', sa.JSON(), nullable=False),
        sa.Column('circles', sa.JSON(), nullable=False),
        sa.Column('set_by', sa.String(length=200), nullable=False),
        sa.Column('set_at', sa.DateTime(timezone=True), nullable=False),
        sa.ForeignKeyConstraint(['vehicle_id'], ['vehicles.id'], ondelete='CASCADE'),
        sa.PrimaryKeyConstraint('vehicle_id'),
    )


def downgrade() -> None:
    """Downgrade schema."""
    op.drop_table('vehicle_plan_extras')
